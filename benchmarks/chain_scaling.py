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

With --builds, each size runs in a fresh process per meson build directory (SYSSIMX_BUILD_DIR,
with the Python package of the source tree it was built from), the builds in turn, so that two
engines (an earlier one kept aside and the current one) are compared in one run. With --rounds R
the whole comparison runs R times in turn and ends with the median and range of each figure:
on a shared machine one run at 10 000 varies by half its value.

    python benchmarks/chain_scaling.py [--sizes 100,1000,10000] [--repeats 3]
                                       [--builds build/before,build/dev] [--direct]
                                       [--rounds 5]
"""

from __future__ import annotations

import argparse
import json
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
    gain_fmu = fmus.path("gain")
    gains = [FMUComponent(f"G{i}", gain_fmu) for i in range(n)]
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


def costs_together(sizes: list[int], runs: int) -> dict[int, list[float]]:
    """CPU nanoseconds per FMU step of each size in `runs` runs, the sizes built side by side
    in this process and run in turn, run by run: a machine whose speed drifts (other virtual
    machines on the host sharing its caches) slows every size alike."""
    chains = {n: chain(n) for n in sizes}
    per_step: dict[int, list[float]] = {n: [] for n in sizes}
    for run in range(runs):
        # each size first in turn: no size always runs right after the same one
        for n in sizes[run % len(sizes):] + sizes[:run % len(sizes)]:
            system = chains[n][0]
            steps = FMU_STEPS // n
            system.initialize(0.0)
            start = time.process_time()
            system.run(0.0, steps * 1e-3, 1e-3)
            per_step[n].append((time.process_time() - start) / (n * steps) * 1e9)
    for system, gains in chains.values():
        system.reset()
        for gain in gains:
            gain.free()
    return per_step


def source_of(build: str) -> str:
    """The source tree a meson build directory was configured from."""
    with open(os.path.join(build, "meson-info", "meson-info.json")) as info:
        return str(json.load(info)["directories"]["source"])


def cost_in_build(build: str, n: int, repeats: int) -> float:
    """cost_per_step in a fresh process on the engine of a meson build directory."""
    # the build's own Python package: an earlier engine with the Python of its time
    environment = dict(os.environ, SYSSIMX_BUILD_DIR=os.path.abspath(build),
                       PYTHONPATH=os.path.join(source_of(build), "python"))
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


def print_table(title: str, sizes: list[int], builds: list[str | None],
                costs: dict[tuple[int, int], list[float]], direct: dict[int, list[float]]) -> None:
    """One table: per size, each build's cost per FMU step (median over the runs, with their
    range when several), its ratio to the first size, the last build against the first and the
    bare C loop."""
    print(title)
    print(f"{'N':>7}" + "".join(f" {build or 'ns':>23}{'ratio':>8}" for build in builds)
          + ("" if len(builds) == 1 else f"{'new/old':>9}")
          + (f"{'direct C loop':>24}{'ratio':>8}{'engine/C':>10}" if direct else ""))

    def cell(values: list[float]) -> str:
        median = statistics.median(values)
        spread = f" ({min(values):.0f}-{max(values):.0f})" if len(values) > 1 else ""
        return f"{median:.1f}{spread}"

    for n in sizes:
        line = f"{n:>7}"
        medians = [statistics.median(costs[n, b]) for b in range(len(builds))]
        for b, median in enumerate(medians):
            base = statistics.median(costs[sizes[0], b])
            line += f"{cell(costs[n, b]):>24}{median / base:>7.2f}x"
        if len(builds) > 1:
            line += f"{medians[-1] / medians[0]:>8.2f}x"
        if direct:
            bare = statistics.median(direct[n])
            line += (f"{cell(direct[n]):>24}{bare / statistics.median(direct[sizes[0]]):>7.2f}x"
                     f"{medians[-1] / bare:>9.2f}x")
        print(line, flush=True)


def print_together(sizes: list[int], runs: int) -> None:
    per_step = costs_together(sizes, runs)
    print(f"chain of gain FMUs, {FMU_STEPS} FMU steps per run, CPU time, the sizes in one "
          f"process run in turn, {runs} runs each; ns per FMU step and ratio to N={sizes[0]}")
    print(f"{'N':>7}{'minimum':>10}{'ratio':>8}{'median':>10}{'ratio':>8}  runs")
    best = min(per_step[sizes[0]])
    middle = statistics.median(per_step[sizes[0]])
    for n in sizes:
        runs_of_n = per_step[n]
        print(f"{n:>7}{min(runs_of_n):>10.1f}{min(runs_of_n) / best:>7.2f}x"
              f"{statistics.median(runs_of_n):>10.1f}"
              f"{statistics.median(runs_of_n) / middle:>7.2f}x  "
              + " ".join(f"{value:.0f}" for value in runs_of_n), flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", default="100,1000,10000")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--rounds", type=int, default=1,
                        help="measure every size and build this many times in turn, then "
                             "print the medians and ranges")
    parser.add_argument("--builds", help="meson build directories to compare, comma-separated")
    parser.add_argument("--direct", action="store_true",
                        help="also the chain stepped by a C loop straight through FMI")
    parser.add_argument("--together", type=int, metavar="RUNS",
                        help="build every size in this one process and run them in turn, "
                             "RUNS runs each; print each size's runs, minimum and median")
    parser.add_argument("--child", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child is not None:
        print(cost_per_step(args.child, args.repeats))
        return
    if args.together is not None:
        print_together([int(n) for n in args.sizes.split(",")], args.together)
        return
    sizes = [int(n) for n in args.sizes.split(",")]
    builds = args.builds.split(",") if args.builds else [None]
    direct_build = builds[-1] or os.environ.get("SYSSIMX_BUILD_DIR", "")
    if args.direct and not direct_build:
        parser.error("--direct runs the C loop of a meson build directory: name it with "
                     "--builds or SYSSIMX_BUILD_DIR")
    print(f"chain of gain FMUs, {FMU_STEPS} FMU steps per run, CPU time, median of "
          f"{args.repeats} runs per process; ns per FMU step and ratio to N={sizes[0]}")
    costs: dict[tuple[int, int], list[float]] = {(n, b): [] for n in sizes
                                                 for b in range(len(builds))}
    direct: dict[int, list[float]] = {n: [] for n in sizes} if args.direct else {}
    for round_number in range(1, args.rounds + 1):
        for n in sizes:
            for b, build in enumerate(builds):
                costs[n, b].append(cost_per_step(n, args.repeats) if build is None
                                   else cost_in_build(build, n, args.repeats))
            if args.direct:
                direct[n].append(cost_direct(direct_build, n))
        this_round = {key: values[-1:] for key, values in costs.items()}
        print_table(f"round {round_number}" if args.rounds > 1 else "", sizes, builds,
                    this_round, {n: values[-1:] for n, values in direct.items()})
    if args.rounds > 1:
        print_table(f"median (range) of {args.rounds} rounds", sizes, builds, costs, direct)


if __name__ == "__main__":
    main()
