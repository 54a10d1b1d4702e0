"""Cost per FMU step as a system grows: a chain of N `gain` FMUs (each driven by the one
before, Gauss-Seidel, one thread), N = 100, 1000, 10000, with N x steps held at 2 000 000 FMU
steps, in one run. Printed: nanoseconds per FMU step (the run's CPU time over N x steps, recording
included: on a shared machine the wall time counts the other processes' turns too) and the
ratio to the smallest N. The gain FMU's own doStep costs about 10 ns
(fmu_step_cost.py), so the rest is the engine's: the inputs set, the outputs read, the
coupling and the history row.

    python benchmarks/chain_scaling.py [--sizes 100,1000,10000] [--repeats 3]
"""

from __future__ import annotations

import argparse
import statistics
import time

from syssimx import Connection, FMUComponent, System, fmus

FMU_STEPS = 2_000_000


def chain(n: int) -> tuple[System, list[FMUComponent]]:
    system = System(f"chain of {n}")
    gains = [FMUComponent(f"G{i}", fmus.path("gain")) for i in range(n)]
    for gain in gains:
        system.add_component(gain)
    for i in range(1, n):
        system.add_connection(Connection(f"G{i - 1}", "y", f"G{i}", "u"))
    gains[0].set_inputs({"u": 1.0})
    return system, gains


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", default="100,1000,10000")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    sizes = [int(n) for n in args.sizes.split(",")]
    print(f"chain of gain FMUs, {FMU_STEPS} FMU steps per run, median of {args.repeats}")
    print(f"{'N':>7}{'steps':>8}{'ns per FMU step':>17}{'ratio':>8}")
    first = None
    for n in sizes:
        system, gains = chain(n)
        steps = FMU_STEPS // n
        walls = []
        for _ in range(args.repeats):
            system.initialize(0.0)
            start = time.process_time()
            system.run(0.0, steps * 1e-3, 1e-3)
            walls.append(time.process_time() - start)
        cost = statistics.median(walls) / (n * steps) * 1e9
        first = first or cost
        print(f"{n:>7}{steps:>8}{cost:>17.1f}{cost / first:>7.2f}x")
        system.reset()
        for gain in gains:
            gain.free()


if __name__ == "__main__":
    main()
