"""The two NetCDF writers an ensemble's `.nc` file can have, side by side in one run: h5netcdf
(netCDF4/HDF5) and scipy (netCDF3, what the `ensemble` extra installs: this comparison chose it;
h5netcdf and h5py must be installed to run it). The dataset is an
EnsembleResult's (member x sample outputs, events, per-member status and statistics) of synthetic
members shaped like a sweep's; the figures are write time (best of REPEATS), file size and read
time, as ratios scipy / h5netcdf.

    python benchmarks/netcdf_backends.py [--members 200] [--samples 2001] [--repeats 3]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr
from syssimx.ensemble.member import MemberResult
from syssimx.ensemble.result import EnsembleResult


def ensemble(members: int, samples: int) -> EnsembleResult:
    """Members of a pendulum-like sweep: three outputs, two events each."""
    time_axis = np.linspace(0.0, 10.0, samples)
    results = []
    for index in range(members):
        theta0 = 0.1 + 0.4 * index / max(members - 1, 1)
        theta = theta0 * np.cos(3.13 * time_axis)
        results.append(MemberResult(
            index, {"P.theta0": theta0}, "ok", time=time_axis,
            micro=np.zeros(samples, dtype=np.int64),
            outputs={"P.theta": theta, "P.omega": -3.13 * theta0 * np.sin(3.13 * time_axis),
                     "P.alpha": -9.8 * theta},
            events=[(0.5, 0, "P.wall_hit"), (1.5, 0, "P.wall_hit")]))
    return EnsembleResult(results, ["P.theta0"], 0.0, 10.0, 10.0 / (samples - 1), 1.0)


def measure(result: EnsembleResult, engine: str, folder: Path, repeats: int
            ) -> tuple[float, int, float]:
    dataset = result._netcdf_dataset()
    path = folder / f"{engine}.nc"
    writes = []
    for _ in range(repeats):
        path.unlink(missing_ok=True)
        start = time.perf_counter()
        dataset.to_netcdf(path, engine=engine)
        writes.append(time.perf_counter() - start)
    start = time.perf_counter()
    with xr.open_dataset(path, engine=engine) as read:
        read.load()
    return min(writes), path.stat().st_size, time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--members", type=int, default=200)
    parser.add_argument("--samples", type=int, default=2001)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    result = ensemble(args.members, args.samples)
    with tempfile.TemporaryDirectory() as folder:
        figures = {engine: measure(result, engine, Path(folder), args.repeats)
                   for engine in ("h5netcdf", "scipy")}
    print(f"{args.members} members x {args.samples} samples x 3 outputs")
    print(f"{'writer':<10} {'write [s]':>10} {'size [MB]':>10} {'read [s]':>10}")
    for engine, (write, size, read) in figures.items():
        print(f"{engine:<10} {write:>10.3f} {size / 1e6:>10.2f} {read:>10.3f}")
    (hw, hs, hr), (sw, ss, sr) = figures["h5netcdf"], figures["scipy"]
    print(f"scipy / h5netcdf: write {sw / hw:.2f}x, size {ss / hs:.2f}x, read {sr / hr:.2f}x")


if __name__ == "__main__":
    main()
