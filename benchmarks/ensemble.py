"""Ensembles on Dask against the same members run one after another in this process.

  seed      the seed scenario (examples/pendulum_wall.py, CVODE FMU): 1 s, dt 0.05, one wall
            hit located by rollback; theta0 swept over 0.2..0.6
  coupled   the coupled pendulums (examples/coupled_pendulums.py: two CVODE pendulums and the
            torsion spring FMU, Gauss-Seidel): 2 s, dt 0.01; P1.theta0 swept over 0.2..0.6

Sequential runs each member with the very function a worker runs (syssimx.ensemble.run_member:
build the System, set the parameters, initialize, run, copy the samples out). The cluster is
the embedded LocalCluster of one worker process per core. Printed, in one run:
- the fixed cost of the embedded cluster: start (scheduler and workers up) and close;
- per scenario and member count: sequential wall, the sweep's wall on the started cluster,
  the speed-up, a member's own time alone and inside a worker (the difference is the cores
  the workers did not get), Dask's cost per member (cluster wall x workers / members minus a
  member's time in its worker), and the speed-up counting the embedded cluster's start and
  close;
- memory: each worker's resident size after start and after all sweeps;
- how much of a seed member is reading its FMUs' model descriptions (read_fmu, once per
  FMUComponent a member builds).

    python benchmarks/ensemble.py [--members 50,200,800] [--workers N]
"""

from __future__ import annotations

import argparse
import functools
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
import coupled_pendulums
import pendulum_wall
from syssimx import FMUComponent, GaussSeidelAlgorithm, System
from syssimx.components.model_description import read_fmu
from syssimx.ensemble import MemberTask, run_member, sweep
from syssimx.ensemble.cluster import cores, ensemble_client

MB = 1024 * 1024


def seed_system() -> System:
    return pendulum_wall.build("cvode")[0]


SCENARIOS: dict[str, tuple[Callable[[], System], str, float, float]] = {
    "seed": (seed_system, "P.theta0", 1.0, 0.05),
    "coupled": (functools.partial(coupled_pendulums.build, GaussSeidelAlgorithm()),
                "P1.theta0", 2.0, 0.01),
}


def resident_size() -> int:
    import psutil

    return psutil.Process().memory_info().rss


def sequential(build: Callable[[], System], name: str, values: np.ndarray, tf: float,
               dt: float) -> float:
    start = time.perf_counter()
    for index, value in enumerate(values):
        member = run_member(build, MemberTask(index, {name: float(value)}, 0.0, tf, dt))
        assert member.ok, member.error
    return time.perf_counter() - start


def on_cluster(client: object, build: Callable[[], System], name: str, values: np.ndarray,
               tf: float, dt: float) -> tuple[float, float]:
    """The sweep's wall time, and the mean wall time of one member inside its worker."""
    start = time.perf_counter()
    result = sweep(build, {name: values}, t0=0.0, tf=tf, dt=dt, client=client, progress=False)
    assert not result.failed, result.failed[0].error
    return time.perf_counter() - start, float(np.mean([m.wall_time for m in result.members]))


def description_share(repeats: int = 50) -> tuple[float, float]:
    """A seed member's mean wall time in this process, and the part of it spent in read_fmu
    for the FMUs its System builds."""
    build, name, tf, dt = SCENARIOS["seed"]
    paths = [c.fmu_path for c in build().components.values() if isinstance(c, FMUComponent)]
    start = time.perf_counter()
    for _ in range(repeats):
        for path in paths:
            read_fmu(path)
    reading = (time.perf_counter() - start) / repeats
    start = time.perf_counter()
    for index in range(repeats):
        run_member(build, MemberTask(index, {name: 0.3}, 0.0, tf, dt))
    return (time.perf_counter() - start) / repeats, reading


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--members", default="50,200,800",
                        help="member counts for the seed scenario (comma-separated)")
    parser.add_argument("--workers", type=int, default=cores())
    args = parser.parse_args()
    counts = [int(n) for n in args.members.split(",")]
    workers = args.workers

    member, reading = description_share()
    load_before = os.getloadavg()[0]
    start = time.perf_counter()
    with ensemble_client(workers=workers) as client:
        started = time.perf_counter() - start
        rss_start = client.run(resident_size)
        rows = []
        for scenario, member_counts in (("seed", counts), ("coupled", [200])):
            build, name, tf, dt = SCENARIOS[scenario]
            on_cluster(client, build, name, np.linspace(0.2, 0.6, workers), tf, dt)  # warm
            for count in member_counts:
                values = np.linspace(0.2, 0.6, count)
                alone = sequential(build, name, values, tf, dt)
                parallel, in_worker = on_cluster(client, build, name, values, tf, dt)
                rows.append((scenario, count, alone, parallel, in_worker))
        rss_end = client.run(resident_size)
        closing = time.perf_counter()
    closed = time.perf_counter() - closing

    print(f"{cores()} cores, load average {load_before:.1f} before, {os.getloadavg()[0]:.1f} "
          "after (other processes share the cores)")
    print(f"embedded cluster, {workers} workers: start {started:.2f} s, close {closed:.2f} s")
    print(f"{'scenario':<9}{'members':>8}{'sequential':>12}{'cluster':>10}{'speed-up':>10}"
          f"{'per member':>12}{'in worker':>11}{'scheduling':>12}{'embedded':>10}")
    for scenario, count, alone, parallel, in_worker in rows:
        per_member = alone / count
        scheduling = parallel * workers / count - in_worker
        embedded = started + parallel + closed
        print(f"{scenario:<9}{count:>8}{alone:>11.2f}s{parallel:>9.2f}s{alone / parallel:>9.2f}x"
              f"{per_member * 1e3:>10.2f}ms{in_worker * 1e3:>9.2f}ms{scheduling * 1e3:>10.2f}ms"
              f"{alone / embedded:>9.2f}x")
    print("(per member: sequential wall / members; in worker: a member's own wall time inside "
          "its worker, above per member when the workers do not get a core each; scheduling: "
          "cluster wall x workers / members minus in worker, Dask's cost per member; embedded: "
          "sequential wall / (start + cluster + close))")
    for address in rss_start:
        print(f"worker {address}: resident {rss_start[address] / MB:.0f} MB after start, "
              f"{rss_end[address] / MB:.0f} MB after all sweeps")
    print(f"a seed member in this process: {member * 1e3:.2f} ms, of which read_fmu (model "
          f"descriptions) {reading * 1e3:.2f} ms ({reading / member:.0%})")
    print(f"this process (sequential runs, the client and the scheduler): "
          f"{resident_size() / MB:.0f} MB")


if __name__ == "__main__":
    main()
