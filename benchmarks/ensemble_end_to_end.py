"""`sweep(workers=W)` end to end (the embedded cluster's start and close included) against a
plain loop in this process, on the seed scenario (examples/pendulum_wall.py, CVODE FMU, 1 s,
dt 0.05, one wall hit; theta0 swept over 0.2..0.6).

The plain loop is what a user writes without ensembles: one System, and per member
set_parameters, initialize, run, and a copy of the samples. Printed, in one run and in turns
(`--repeats` times each, best and median):
- each in a fresh Python process of its own (what a user's script costs: the interpreter,
  the imports and the first member's one-time loading included), the process's wall;
- in this process, after both have run once (warm: with the embedded cluster's forked workers,
  what this process loaded is loaded there too): the loop's wall, the sweep's wall with the
  cluster started and closed inside it, their ratio;
- on an already started cluster: the sweep's wall, the CPU the client process (client,
  scheduler, nannies) spent per member and how much of it the process spends idle anyway
  (per second of wall, times the sweep's wall), the workers' CPU per member, and the loop's.

    python benchmarks/ensemble_end_to_end.py [--members 2000] [--workers W] [--repeats 3]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
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
    """The loop's wall (its CPU per member in LOOP_CPU)."""
    start, cpu = time.perf_counter(), time.process_time()
    system = seed_system()
    pendulum = system.components["P"]
    kept = []
    for value in values:
        pendulum.set_parameters(theta0=float(value))
        system.initialize(0.0)
        result = system.run(0.0, TF, DT)
        t, outputs = result["P"]
        kept.append((t.copy(), {name: series.copy() for name, series in outputs.items()}))
    LOOP_CPU.append((time.process_time() - cpu) / len(values))
    return time.perf_counter() - start


LOOP_CPU: list[float] = []


def end_to_end(values: np.ndarray, workers: int) -> float:
    start = time.perf_counter()
    result = sweep(seed_system, {"P.theta0": values}, t0=0.0, tf=TF, dt=DT, workers=workers,
                   progress=False)
    assert not result.failed, result.failed[0].error
    return time.perf_counter() - start


def process_cpu() -> float:
    return time.process_time()


def fresh_process(kind: str, members: int, workers: int) -> float:
    """The wall of a fresh Python process running the loop or the sweep alone."""
    start = time.perf_counter()
    subprocess.run([sys.executable, __file__, "--alone", kind, "--members", str(members),
                    "--workers", str(workers)], check=True)
    return time.perf_counter() - start


def idle_cpu_per_second(client: object, seconds: float = 2.0) -> float:
    """The client process's CPU per second of wall with the cluster started and idle."""
    del client  # held: its cluster runs in this process
    cpu = time.process_time()
    time.sleep(seconds)
    return (time.process_time() - cpu) / seconds


def on_started(values: np.ndarray, workers: int, repeats: int
               ) -> tuple[float, float, float, float]:
    """Best wall of the sweep on a started cluster; client and worker CPU per member; the
    client process's idle CPU per second."""
    walls, client_cpu, worker_cpu = [], [], []
    with ensemble_client(workers=workers) as client:
        sweep(seed_system, {"P.theta0": values[:4 * workers]}, t0=0.0, tf=TF, dt=DT,
              client=client, progress=False)  # the workers import and build once
        idle = idle_cpu_per_second(client)
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
    return min(walls), min(client_cpu) / count, min(worker_cpu) / count, idle


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--members", type=int, default=2000)
    parser.add_argument("--workers", type=int, default=cores())
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--alone", choices=("loop", "sweep"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    values = np.linspace(0.2, 0.6, args.members)
    if args.alone is not None:  # one side of the fresh-process comparison
        plain_loop(values) if args.alone == "loop" else end_to_end(values, args.workers)
        return
    load = os.getloadavg()[0]
    fresh_loops, fresh_sweeps, loops, sweeps = [], [], [], []
    for _ in range(args.repeats):
        fresh_loops.append(fresh_process("loop", args.members, args.workers))
        fresh_sweeps.append(fresh_process("sweep", args.members, args.workers))
    plain_loop(values[:2])  # this process loads what a member needs once (pint: 2.5 s)
    for _ in range(args.repeats):
        loops.append(plain_loop(values))
        sweeps.append(end_to_end(values, args.workers))
    started, client_cpu, worker_cpu, idle = on_started(values, args.workers, args.repeats)
    print(f"{cores()} cores, load average {load:.1f} before, {os.getloadavg()[0]:.1f} after; "
          f"{args.members} seed members, {args.workers} workers, {args.repeats} repeats")
    print(f"{'':<44}{'best':>9}{'median':>9}")

    def row(label: str, loop: list[float], swept: list[float]) -> None:
        print(f"{'plain loop, ' + label:<44}{min(loop):>8.2f}s{statistics.median(loop):>8.2f}s")
        print(f"{'sweep(workers=W), ' + label:<44}{min(swept):>8.2f}s"
              f"{statistics.median(swept):>8.2f}s")
        print(f"{'  speed-up':<44}{min(loop) / min(swept):>8.2f}x"
              f"{statistics.median(loop) / statistics.median(swept):>8.2f}x")

    row("fresh process each", fresh_loops, fresh_sweeps)
    row("warm, cluster start and close in", loops, sweeps)
    print(f"{'sweep on a started cluster':<44}{started:>8.2f}s  "
          f"({min(loops) / started:.2f}x the loop's best)")
    idle_share = idle * started / args.members
    print(f"per member: loop {min(loops) / args.members * 1e3:.3f} ms wall, "
          f"{min(LOOP_CPU) * 1e3:.3f} ms CPU; workers {worker_cpu * 1e3:.3f} ms CPU; client "
          f"process (client, scheduler, nannies) {client_cpu * 1e3:.3f} ms CPU, of which idle "
          f"{idle_share * 1e3:.3f} ms ({idle * 1e3:.1f} ms per second), without the idle "
          f"share {(client_cpu - idle_share) * 1e3:.3f} ms")


if __name__ == "__main__":
    main()
