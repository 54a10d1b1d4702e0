"""`sweep(workers=W)` end to end (the embedded cluster's start and close included) against a
plain loop in this process, on the seed scenario (examples/pendulum_wall.py, CVODE FMU, 1 s,
dt 0.05, one wall hit; theta0 swept over 0.2..0.6).

The plain loop is what a user writes without ensembles: one System, and per member
set_parameters, initialize, run, and a copy of the samples. Printed, in one run and in turns
(`--repeats` times each, best and median): the loop's wall, the sweep's wall with the cluster
started and closed inside it, their ratio, and on an already started cluster the sweep's wall
and the CPU the client process (client, scheduler, nannies) spent per member, with the workers'
CPU per member beside it.

    python benchmarks/ensemble_end_to_end.py [--members 2000] [--workers W] [--repeats 3]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
import pendulum_wall
from syssimx import System
from syssimx.ensemble import sweep
from syssimx.ensemble.cluster import cores, ensemble_client

TF, DT = 1.0, 0.05


def seed_system() -> System:
    return pendulum_wall.build("cvode")[0]


def plain_loop(values: np.ndarray) -> float:
    start = time.perf_counter()
    system = seed_system()
    pendulum = system.components["P"]
    kept = []
    for value in values:
        pendulum.set_parameters(theta0=float(value))
        system.initialize(0.0)
        result = system.run(0.0, TF, DT)
        t, outputs = result["P"]
        kept.append((t.copy(), {name: series.copy() for name, series in outputs.items()}))
    return time.perf_counter() - start


def end_to_end(values: np.ndarray, workers: int) -> float:
    start = time.perf_counter()
    result = sweep(seed_system, {"P.theta0": values}, t0=0.0, tf=TF, dt=DT, workers=workers,
                   progress=False)
    assert not result.failed, result.failed[0].error
    return time.perf_counter() - start


def process_cpu() -> float:
    return time.process_time()


def on_started(values: np.ndarray, workers: int, repeats: int) -> tuple[float, float, float]:
    """Best wall of the sweep on a started cluster; client and worker CPU per member."""
    walls, client_cpu, worker_cpu = [], [], []
    with ensemble_client(workers=workers) as client:
        sweep(seed_system, {"P.theta0": values[:4 * workers]}, t0=0.0, tf=TF, dt=DT,
              client=client, progress=False)  # the workers import and build once
        for _ in range(repeats):
            before_workers = sum(client.run(process_cpu).values())
            cpu, start = process_cpu(), time.perf_counter()
            result = sweep(seed_system, {"P.theta0": values}, t0=0.0, tf=TF, dt=DT,
                           client=client, progress=False)
            walls.append(time.perf_counter() - start)
            client_cpu.append(process_cpu() - cpu)
            worker_cpu.append(sum(client.run(process_cpu).values()) - before_workers)
            assert not result.failed, result.failed[0].error
    count = len(values)
    return min(walls), min(client_cpu) / count, min(worker_cpu) / count


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--members", type=int, default=2000)
    parser.add_argument("--workers", type=int, default=cores())
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    values = np.linspace(0.2, 0.6, args.members)
    load = os.getloadavg()[0]
    loops, sweeps = [], []
    for _ in range(args.repeats):
        loops.append(plain_loop(values))
        sweeps.append(end_to_end(values, args.workers))
    started, client_cpu, worker_cpu = on_started(values, args.workers, args.repeats)
    print(f"{cores()} cores, load average {load:.1f} before, {os.getloadavg()[0]:.1f} after; "
          f"{args.members} seed members, {args.workers} workers, {args.repeats} repeats")
    print(f"{'':<38}{'best':>9}{'median':>9}")
    print(f"{'plain loop (one System)':<38}{min(loops):>8.2f}s{statistics.median(loops):>8.2f}s")
    print(f"{'sweep(workers=W), start and close in':<38}{min(sweeps):>8.2f}s"
          f"{statistics.median(sweeps):>8.2f}s")
    print(f"{'speed-up end to end':<38}{min(loops) / min(sweeps):>8.2f}x"
          f"{statistics.median(loops) / statistics.median(sweeps):>8.2f}x")
    print(f"{'sweep on a started cluster':<38}{started:>8.2f}s  "
          f"({min(loops) / started:.2f}x the loop's best)")
    print(f"per member: loop {min(loops) / args.members * 1e3:.3f} ms; CPU of the client "
          f"process (client, scheduler, nannies) {client_cpu * 1e3:.3f} ms, of the workers "
          f"{worker_cpu * 1e3:.3f} ms")


if __name__ == "__main__":
    main()
