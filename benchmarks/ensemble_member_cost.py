"""Where a seed member's CPU goes in an ensemble worker, against a plain loop, side by side.

The seed scenario (examples/pendulum_wall.py, CVODE FMU, 1 s, dt 0.05, one wall hit), in turns
(`--repeats` times each, best of them), the CPU per member of:
- the plain loop in this process: one System, and per member set_parameters, initialize, run
  and a copy of the samples (what benchmarks/ensemble_end_to_end.py calls the loop);
- the ensemble's own path in this process: one task's members run as a worker runs them
  (`run_chunk`: parameters set on the kept System, its run, the samples recorded, the block
  packed), without Dask;
- the same task in a forked worker of the embedded cluster (`--workers` of them, each given
  one such task at once): the CPU of the thread that ran it, and of the whole worker process
  meanwhile (its event loop: heartbeats, the task's messages, the block's transfer).

Each ratio is to the loop: the ensemble's path over the loop is the ensemble's own Python per
member; the worker's thread over the path here is what the worker process itself changes
(its memory, its caches shared with the other workers); the worker process over its thread is
Dask's cost inside the worker.

    python benchmarks/ensemble_member_cost.py [--members 500] [--workers 1] [--repeats 5]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
import pendulum_wall
from syssimx import System
from syssimx.ensemble.chunk import Experiment, MemberChunk, run_chunk
from syssimx.ensemble.cluster import ensemble_client

TF, DT = 1.0, 0.05


def seed_system() -> System:
    return pendulum_wall.build("cvode")[0]


def loop(values: np.ndarray) -> float:
    """The plain loop's CPU per member (its System built before the clock starts)."""
    system = seed_system()
    pendulum = system.components["P"]
    cpu = time.process_time()
    for value in values:
        pendulum.set_parameters(theta0=float(value))
        system.initialize(0.0)
        t, outputs = system.run(0.0, TF, DT)["P"]
        t.copy(), {name: series.copy() for name, series in outputs.items()}
    return (time.process_time() - cpu) / len(values)


def chunk_cpu(values: np.ndarray, ensemble: str) -> tuple[float, float]:
    """One task of the ensemble's members, run here: (the thread's, the process's) CPU per
    member. Its System is built and its first member run before the clocks start."""
    experiment = Experiment(0.0, TF, DT, None, None, ensemble)
    sets = [{"P.theta0": float(value)} for value in values]
    run_chunk(seed_system, MemberChunk(0, sets[:1], experiment))
    thread, process = time.thread_time(), time.process_time()
    run_chunk(seed_system, MemberChunk(0, sets, experiment))
    return ((time.thread_time() - thread) / len(sets),
            (time.process_time() - process) / len(sets))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--members", type=int, default=500)
    parser.add_argument("--workers", type=int, default=1)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    values = np.linspace(0.2, 0.6, args.members)
    load = os.getloadavg()[0]
    loop(values[:2])  # this process loads what a member needs once (pint)
    loops, here, threads, processes = [], [], [], []
    with ensemble_client(workers=args.workers) as client:
        workers = list(client.nthreads())
        for attempt in range(args.repeats):
            loops.append(loop(values))
            here.append(chunk_cpu(values, f"here-{attempt}")[0])
            futures = [client.submit(chunk_cpu, values, f"worker-{attempt}", workers=[worker],
                                     pure=False) for worker in workers]
            measured = client.gather(futures)
            threads.append(min(thread for thread, _ in measured))
            processes.append(min(process for _, process in measured))
    print(f"load average {load:.1f} before, {os.getloadavg()[0]:.1f} after; {args.members} seed "
          f"members, {args.workers} worker(s) at once, best of {args.repeats}")
    best = min(loops)
    for label, cpu in (("plain loop, this process", best),
                       ("ensemble's path (run_chunk), this process", min(here)),
                       ("the same in a worker: its thread", min(threads)),
                       ("the same in a worker: its whole process", min(processes))):
        print(f"{label:<46}{cpu * 1e3:>8.3f} ms{cpu / best:>8.2f}x")


if __name__ == "__main__":
    main()
