"""Parallel stepping: the same System on one thread and on two (JacobiAlgorithm(threads=N)),
side by side in one run.

  cvode        100 pendulum_cvode FMUs (relative tolerance 1e-10), lightly coupled: each
               pendulum's angle drives the next one's torque (x0.1); 2 s, dt 0.01
  gain         100 gain FMUs (y = k u, nothing to integrate); 20 000 steps
  spring       100 torsion_spring FMUs (four inputs, two outputs, no state); 20 000 steps
  euler dt     100 pendulum_euler FMUs (Euler substeps of 1e-4 s, so dt / 1e-4 of them per
               doStep) at several dt, 2 000 steps each: where threads stop paying

For each case: the wall time per macro step on one thread and on two (median of --repeat
runs, the two alternating), the speed-up (wall 1 / wall 2), the CPU time over the wall time of
each (process CPU, all threads), the machine's 1-minute load average after the case, and
whether the two recorded the same samples to the last bit. Other processes on the cores make
the two-thread figure the first to suffer: measure on a quiet machine.

    python benchmarks/parallel_stepping.py [--repeat N] [--threads N] [--cases euler,gain]
"""

from __future__ import annotations

import argparse
import gc
import os
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from syssimx import Connection, FMUComponent, JacobiAlgorithm, System, fmus

COMPONENTS = 100


@dataclass
class Case:
    name: str
    build: Callable[[int], System]
    tf: float
    dt: float


@dataclass
class Run:
    wall: float
    cpu: float
    samples: np.ndarray


def pendulums(fmu: str, coupled: bool, **parameters: float) -> Callable[[int], System]:
    def build(threads: int) -> System:
        system = System(fmu)
        for i in range(COMPONENTS):
            pendulum = FMUComponent(f"C{i}", fmus.path(fmu))
            pendulum.set_parameters(theta0=0.2 + 0.003 * i, **parameters)
            system.add_component(pendulum)
        for i in range(COMPONENTS - 1):
            if coupled:
                system.add_connection(Connection(f"C{i}", "theta", f"C{i + 1}", "torque",
                                                 factor=0.1, convert_units=False))
        system.set_algorithm(JacobiAlgorithm(threads=threads))
        return system
    return build


def blocks(fmu: str) -> Callable[[int], System]:
    """Tiny FMUs in a chain, each fed by the one before (Jacobi: from the step's start)."""
    def build(threads: int) -> System:
        system = System(fmu)
        for i in range(COMPONENTS):
            system.add_component(FMUComponent(f"C{i}", fmus.path(fmu)))
        for i in range(1, COMPONENTS):
            if fmu == "gain":
                system.add_connection(Connection(f"C{i - 1}", "y", f"C{i}", "u"))
            else:
                system.add_connection(Connection(f"C{i - 1}", "tau1", f"C{i}", "theta1",
                                                 convert_units=False))
        system.set_algorithm(JacobiAlgorithm(threads=threads))
        return system
    return build


def run(case: Case, threads: int) -> Run:
    system = case.build(threads)
    system.initialize(0.0)
    gc.collect()
    wall, cpu = time.perf_counter(), time.process_time()
    result = system.run(0.0, case.tf, case.dt)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    last = f"C{COMPONENTS - 1}"
    samples = np.concatenate([result[last][0], *result[last][1].values()])
    return Run(wall, cpu, samples.copy())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--cases", help="only the cases whose name contains one of these words "
                                        "(comma-separated)")
    args = parser.parse_args()
    cases = [Case("cvode (coupled)", pendulums("pendulum_cvode", True,
                                               cvode_relative_tolerance=1e-10), 2.0, 0.01),
             Case("cvode (uncoupled)", pendulums("pendulum_cvode", False,
                                                 cvode_relative_tolerance=1e-10), 2.0, 0.01),
             Case("gain", blocks("gain"), 2.0, 1e-4),
             Case("spring", blocks("torsion_spring"), 2.0, 1e-4)]
    cases += [Case(f"euler dt={dt:g}", pendulums("pendulum_euler", False), 2000 * dt, dt)
              for dt in (1e-4, 3e-4, 1e-3, 3e-3, 1e-2)]
    if args.cases:
        words = args.cases.split(",")
        cases = [case for case in cases if any(word in case.name for word in words)]
    print(f"load average before: {os.getloadavg()[0]:.2f} (1 min) on {os.cpu_count()} cores; "
          f"{args.repeat} runs each, medians")
    n = args.threads
    print(f"{'case':<20}{'µs/step 1':>11}{f'µs/step {n}':>11}{'speed-up':>10}"
          f"{'CPU/wall 1':>12}{f'CPU/wall {n}':>12}{'load':>7}  same samples")
    for case in cases:
        runs: dict[int, list[Run]] = {1: [], n: []}
        for _ in range(args.repeat):
            for threads in (1, n):
                runs[threads].append(run(case, threads))
        steps = round((case.tf) / case.dt)
        wall = {t: statistics.median(r.wall for r in runs[t]) for t in runs}
        load = {t: statistics.median(r.cpu / r.wall for r in runs[t]) for t in runs}
        same = all(np.array_equal(r.samples, runs[1][0].samples) for r in runs[1] + runs[n])
        print(f"{case.name:<20}{1e6 * wall[1] / steps:>11.1f}{1e6 * wall[n] / steps:>11.1f}"
              f"{wall[1] / wall[n]:>9.2f}x{load[1]:>12.2f}{load[n]:>12.2f}"
              f"{os.getloadavg()[0]:>7.2f}  {same}")
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
