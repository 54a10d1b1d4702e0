"""Event localization methods side by side: iterations and wall time per event, in one run.

Three indicators, two time tolerances (1e-9 and 1e-6), every method of the engine:

  pendulum     the seed scenario (CVODE pendulum against a wall, 1 s, dt 0.05): a smooth
               indicator, theta
  sample_hold  a cosine sampled and held every 1 ms (models/SampleHold), 2 s, dt 0.05, both
               directions: an output that is piecewise constant in the master's time
  BouncingBall the Reference FMUs' BouncingBall (FMI 2.0, fixed internal step 1 ms), indicator
               on v in both directions, 3 s, dt 0.01 (skipped without the Reference FMUs: set
               SYSSIMX_REFERENCE_FMUS to the folder holding fmi2/)

Methods: illinois (the default: Illinois with secant steps, held within bisection's count + 2),
bisection, illinois_unguarded (Illinois alone). Wall time is the median over the repeats of a
whole run divided by its events, so it includes the event-free steps, which are the same for
every method; the ratio to bisection is what to read.

    python benchmarks/localization_methods.py [--repeat N]
"""

from __future__ import annotations

import argparse
import importlib
import os
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

from syssimx import FMUComponent, HybridAlgorithm, System, fmus
from syssimx.system.algorithms.hybrid import locator_methods

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "examples"))
pendulum_wall = importlib.import_module("pendulum_wall")


def reference_ball() -> Path | None:
    folder = Path(os.environ.get("SYSSIMX_REFERENCE_FMUS",
                                 ROOT.parent / "shared" / "reference-fmus"))
    path = folder / "fmi2" / "BouncingBall.fmu"
    return path if path.is_file() else None


def pendulum(method: str, tol_time: float) -> tuple[System, float, float]:
    system, _ = pendulum_wall.build("cvode", method)
    system.algorithm.tol_time = tol_time
    return system, 1.0, 0.05


def sample_hold(method: str, tol_time: float) -> tuple[System, float, float]:
    hold = FMUComponent("H", fmus.path("sample_hold"))
    hold.add_event_indicator("through_zero", variable="y", direction=0)
    return single(hold, method, tol_time), 2.0, 0.05


def bouncing_ball(method: str, tol_time: float) -> tuple[System, float, float]:
    ball = FMUComponent("B", str(reference_ball()))
    ball.add_event_indicator("v_zero", variable="v", direction=0)
    return single(ball, method, tol_time), 3.0, 0.01


def single(component: FMUComponent, method: str, tol_time: float) -> System:
    system = System(component.name)
    system.add_component(component)
    system.set_algorithm(HybridAlgorithm(tol_time=tol_time, method=method))
    return system


Case = Callable[[str, float], tuple[System, float, float]]


def measure(case: Case, method: str, tol_time: float, repeat: int) -> tuple[float, int, float,
                                                                             float]:
    """Mean and worst iterations per event, doStep calls per event, median wall s per event."""
    walls = []
    for _ in range(repeat):
        system, stop, dt = case(method, tol_time)
        system.initialize(0.0)
        start = time.perf_counter()
        result = system.run(0.0, stop, dt)
        walls.append(time.perf_counter() - start)
    counts = [e.iterations for e in result.events if e.micro == 0 and e.iterations > 0]
    n = len(counts)
    return (sum(counts) / n, max(counts), result.statistics.do_step_calls / n,
            statistics.median(walls) / n)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=20)
    repeat = parser.parse_args().repeat
    cases: dict[str, Case] = {"pendulum": pendulum, "sample_hold": sample_hold}
    if reference_ball() is not None:
        cases["BouncingBall"] = bouncing_ball
    else:
        print("Reference BouncingBall not found (set SYSSIMX_REFERENCE_FMUS): skipped")
    methods = list(locator_methods())
    print(f"{'indicator':<13}{'tol_time':>9}  {'method':<19}{'iterations/event':>17}"
          f"{'worst':>6}{'doStep/event':>13}{'wall/event':>12}{'vs bisection':>13}")
    for name, case in cases.items():
        for tol_time in (1e-9, 1e-6):
            rows = {m: measure(case, m, tol_time, repeat) for m in methods}
            base = rows["bisection"][3]
            for method, (mean, worst, do_steps, wall) in rows.items():
                print(f"{name:<13}{tol_time:>9.0e}  {method:<19}{mean:>17.1f}{worst:>6d}"
                      f"{do_steps:>13.1f}{wall * 1e6:>10.0f}us{wall / base:>12.2f}x")


if __name__ == "__main__":
    main()
