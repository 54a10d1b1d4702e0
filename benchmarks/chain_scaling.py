"""Cost per FMU step as a system grows: a chain of N `gain` FMUs (each driven by the one
before, Gauss-Seidel, one thread), N = 100, 1000, 10000, with N x steps held at 2 000 000 FMU
steps, in one run. Printed: nanoseconds per FMU step (the run's CPU time over N x steps, recording
included: on a shared machine the wall time counts the other processes' turns too) and the
ratio to the smallest N. The gain FMU's own doStep costs about 10 ns
(fmu_step_cost.py), so the rest is the engine's: the inputs set, the outputs read, the
coupling and the history row.

With --direct, the same chain stepped straight through FMI 2.0 in a C loop (the build's
tests/c/fmu/chain_direct: set the input, doStep, get the output; the instances made one after
the other) is printed beside it, with the engine's cost over it: the floor of the FMU's own work
and memory.

With --builds, each size runs in a fresh process per meson build directory (SYSSIMX_BUILD_DIR),
the builds in turn, so that two engines (an earlier one kept aside and the current one) are
compared in one run.

    python benchmarks/chain_scaling.py [--sizes 100,1000,10000] [--repeats 3]
                                       [--builds build/before,build/dev] [--direct]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from syssimx import FMUComponent, System

FMU_STEPS = 2_000_000


def chain(n: int) -> tuple[System, list[FMUComponent]]:
    # imported here: with --builds this process only starts others, each on its own engine
    from syssimx import Connection, FMUComponent, System, fmus

    system = System(f"chain of {n}")
    gains = [FMUComponent(f"G{i}", fmus.path("gain")) for i in range(n)]
    for gain in gains:
        system.add_component(gain)
    for i in range(1, n):
        system.add_connection(Connection(f"G{i - 1}", "y", f"G{i}", "u"))
    gains[0].set_inputs({"u": 1.0})
    return system, gains


def cost_per_step(n: int, repeats: int) -> float:
    """Median CPU nanoseconds per FMU step of `repeats` runs of a chain of n."""
    system, gains = chain(n)
    steps = FMU_STEPS // n
    cpu = []
    for _ in range(repeats):
        system.initialize(0.0)
        start = time.process_time()
        system.run(0.0, steps * 1e-3, 1e-3)
        cpu.append(time.process_time() - start)
    system.reset()
    for gain in gains:
        gain.free()
    return statistics.median(cpu) / (n * steps) * 1e9


def cost_in_build(build: str, n: int, repeats: int) -> float:
    """cost_per_step in a fresh process on the engine of a meson build directory."""
    environment = dict(os.environ, SYSSIMX_BUILD_DIR=os.path.abspath(build))
    output = subprocess.run(
        [sys.executable, __file__, "--child", str(n), "--repeats", str(repeats)],
        env=environment, check=True, capture_output=True, text=True).stdout
    return float(output)


def cost_direct(build: str, n: int) -> float:
    """CPU nanoseconds per FMU step of the chain of n in chain_direct, the FMI loop in C."""
    root = os.path.abspath(build)
    models = os.path.join(root, "models")
    output = subprocess.run(
        [os.path.join(root, "tests", "c", "fmu", "chain_direct"),
         os.path.join(models, "gain.so"), os.path.join(models, "gain_modelDescription.xml"),
         str(n), str(FMU_STEPS // n), "u", "y"],
        check=True, capture_output=True, text=True).stdout
    return float(output)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", default="100,1000,10000")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--builds", help="meson build directories to compare, comma-separated")
    parser.add_argument("--direct", action="store_true",
                        help="also the chain stepped by a C loop straight through FMI")
    parser.add_argument("--child", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child is not None:
        print(cost_per_step(args.child, args.repeats))
        return
    sizes = [int(n) for n in args.sizes.split(",")]
    builds = args.builds.split(",") if args.builds else [None]
    print(f"chain of gain FMUs, {FMU_STEPS} FMU steps per run, CPU time, median of "
          f"{args.repeats}; ns per FMU step and ratio to N={sizes[0]}")
    direct_build = builds[-1] or os.environ.get("SYSSIMX_BUILD_DIR", "")
    if args.direct and not direct_build:
        parser.error("--direct runs the C loop of a meson build directory: name it with "
                     "--builds or SYSSIMX_BUILD_DIR")
    print(f"{'N':>7}" + "".join(f"{build or 'ns':>24}{'ratio':>8}" for build in builds)
          + ("" if len(builds) == 1 else f"{'new/old':>9}")
          + (f"{'direct C loop':>15}{'ratio':>8}{'engine/C':>10}" if args.direct else ""))
    first: list[float] = []  # each column's cost at the smallest N
    first_direct = 0.0
    for n in sizes:
        costs = [cost_per_step(n, args.repeats) if build is None
                 else cost_in_build(build, n, args.repeats) for build in builds]
        line = f"{n:>7}"
        first = first or costs
        for cost, base in zip(costs, first, strict=True):
            line += f"{cost:>24.1f}{cost / base:>7.2f}x"
        if len(builds) > 1:
            line += f"{costs[-1] / costs[0]:>8.2f}x"
        if args.direct:
            direct = cost_direct(direct_build, n)
            first_direct = first_direct or direct
            line += f"{direct:>15.1f}{direct / first_direct:>7.2f}x{costs[-1] / direct:>9.2f}x"
        print(line, flush=True)


if __name__ == "__main__":
    main()
