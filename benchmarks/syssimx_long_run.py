"""Long hybrid runs cost linearly in their length.

The pendulum against an elastic wall (declarative path: indicator on theta evaluated in C,
Python handler once per event), Euler FMU, dt 1e-3, for 10, 100 and 1000 s: about one event
every 0.93 s. Prints wall time, cost per macro step and per event, and the history size, with
ratios to the shortest run. SysSimX 0.4.3 grows quadratically here (each checkpoint copies the
whole history): 0.31 / 4.5 / 68.7 s for 1 000 / 4 000 / 16 000 macro steps.

    python benchmarks/syssimx_long_run.py [--lengths 10 100 1000] [--dt 1e-3]
"""

from __future__ import annotations

import argparse
import importlib
import sys
import time
from pathlib import Path

from syssimx import System

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
pendulum_wall = importlib.import_module("pendulum_wall")


def pendulum_with_wall() -> System:
    system, _ = pendulum_wall.build("euler")
    return system


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lengths", type=float, nargs="+", default=[10.0, 100.0, 1000.0])
    parser.add_argument("--dt", type=float, default=1e-3)
    args = parser.parse_args()
    print(f"pendulum with elastic wall, Euler FMU, dt {args.dt}")
    header = (f"{'length s':>9}{'steps':>10}{'events':>8}{'wall s':>9}{'us/step':>9}"
              f"{'wall ratio':>11}{'length ratio':>13}{'history MB':>11}")
    print(header)
    print("-" * len(header))
    first: tuple[float, float] | None = None
    for length in args.lengths:
        system = pendulum_with_wall()
        start = time.perf_counter()
        result = system.run(0.0, length, args.dt)
        wall = time.perf_counter() - start
        steps = result.statistics.macro_steps
        history_mb = system.history_bytes() / 1e6
        first = first or (wall, length)
        print(f"{length:>9.0f}{steps:>10}{len(result.events):>8}{wall:>9.3f}"
              f"{wall / steps * 1e6:>9.2f}{wall / first[0]:>11.1f}{length / first[1]:>13.0f}"
              f"{history_mb:>11.1f}")


if __name__ == "__main__":
    main()
