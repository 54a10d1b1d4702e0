"""FMI 3.0 against FMI 2.0 builds of the same model, side by side in one run.

Per doStep: the pendulum with CVODE and with Euler (pendulum_cvode, pendulum_cvode_fmi3,
pendulum_euler, pendulum_euler_fmi3), free swinging, 20 000 steps of 1 ms in one System.run,
no events: wall time per engine step. Both builds run the same C model and solver; the
difference is the FMI 3.0 binding (the value-reference type table, doStep's out-arguments)
and the FMU's own entry points, best seen on the cheap Euler step.

Per event: the bouncing ball dropped from 1 m (e = 0.8, 3.5 s, dt 0.01, 7 bounces):
  fmi3 early return  bouncing_ball_cvode_fmi3: CVODE finds the floor, the FMU returns early,
                     syssimx handles the event in event mode (no rollback)
  fmi2 rollback      bouncing_ball_continuous_cvode: the master's floor indicator on h is
                     located by rollback (Illinois, tol_time 1e-10) and the ball is
                     reinitialized with the reversed velocity (examples/bouncing_ball.py)
Wall time per event is the median whole run divided by its bounces (the event-free steps are
the same 350 for both); doStep calls and state restores are the FMU's own counters for the
whole run (350 of the doSteps are the grid's).

The runs alternate between the two builds, REPEAT times each; medians are printed.

    python benchmarks/fmi3_vs_fmi2.py [--repeat N]
"""

from __future__ import annotations

import argparse
import importlib
import math
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

from syssimx import FMUComponent, HybridAlgorithm, System, fmus

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "examples"))
bouncing_ball = importlib.import_module("bouncing_ball")

STEPS, DT = 20_000, 1e-3
BALL_STOP, BALL_DT = 3.5, 0.01


def pendulum(stem: str) -> System:
    component = FMUComponent("P", fmus.path(stem))
    component.set_parameters(theta0=0.5, omega0=0.0)
    system = System(stem)
    system.add_component(component)
    system.initialize(0.0)
    return system


def ball_fmi3() -> tuple[System, FMUComponent]:
    ball = FMUComponent("Ball", fmus.path("bouncing_ball_cvode_fmi3"))
    ball.set_parameters(h0=bouncing_ball.H0, v0=0.0, g=bouncing_ball.G,
                        e=bouncing_ball.RESTITUTION, cvode_relative_tolerance=1e-10)
    system = System("ball fmi3")
    system.add_component(ball)
    system.initialize(0.0)
    return system, ball


def ball_fmi2() -> tuple[System, FMUComponent]:
    system = bouncing_ball.build(cvode_relative_tolerance=1e-10)
    system.set_algorithm(HybridAlgorithm(tol_time=1e-10, zeno_min_interval=1e-4))
    system.initialize(0.0)
    return system, system.components["Ball"]


def per_step(stem: str) -> float:
    system = pendulum(stem)
    started = time.perf_counter()
    system.run(0.0, STEPS * DT, DT)
    return (time.perf_counter() - started) / STEPS


def per_event(build: Callable[[], tuple[System, FMUComponent]]) -> tuple[float, int, int, int]:
    """Wall s per event, events, the FMU's doStep calls and state restores in the run."""
    system, ball = build()
    started = time.perf_counter()
    result = system.run(0.0, BALL_STOP, BALL_DT)
    wall = time.perf_counter() - started
    events = len(result.events)
    counters = ball.instance.counters()
    return wall / events, events, counters["do_step"], counters["set_state"]


def bounce_times(build: Callable[[], tuple[System, FMUComponent]]) -> list[float]:
    system, _ = build()
    return [e.t for e in system.run(0.0, BALL_STOP, BALL_DT).events]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    repeat = parser.parse_args().repeat

    steps: dict[str, list[float]] = {stem: [] for solver in ("cvode", "euler")
                                     for stem in (f"pendulum_{solver}", f"pendulum_{solver}_fmi3")}
    events: dict[str, list[tuple[float, int, int, int]]] = {"fmi3": [], "fmi2": []}
    builds = {"fmi3": ball_fmi3, "fmi2": ball_fmi2}
    for _ in range(repeat):
        for stem in steps:
            steps[stem].append(per_step(stem))
        for name, build in builds.items():
            events[name].append(per_event(build))

    print(f"per doStep (pendulum, {STEPS} steps of {DT} s, median of {repeat}):")
    for solver in ("cvode", "euler"):
        fmi2_step = statistics.median(steps[f"pendulum_{solver}"])
        fmi3_step = statistics.median(steps[f"pendulum_{solver}_fmi3"])
        print(f"  {solver:<6} FMI 2.0 {fmi2_step * 1e6:8.2f} us   FMI 3.0 {fmi3_step * 1e6:8.2f} "
              f"us   FMI 3.0 / FMI 2.0 = {fmi3_step / fmi2_step:.2f}")

    t1 = math.sqrt(2 * bouncing_ball.H0 / bouncing_ball.G)
    exact = [t1 + 2 * t1 * sum(bouncing_ball.RESTITUTION**k for k in range(1, n))
             for n in range(1, 8)]
    print(f"\nper event (bouncing ball, {BALL_STOP} s, dt {BALL_DT}, median of {repeat}):")
    print("  build              events  wall/event   doSteps  restores  worst |t - closed form|")
    walls = {}
    for name, label in (("fmi3", "FMI 3.0 early ret."), ("fmi2", "FMI 2.0 rollback")):
        runs = events[name]
        walls[name] = statistics.median(run[0] for run in runs)
        _, count, do_steps, restores = runs[-1]
        times = bounce_times(builds[name])
        error = max(abs(t - e) for t, e in zip(times, exact, strict=False))
        print(f"  {label:<18} {count:6d}  {walls[name] * 1e3:8.3f} ms  {do_steps:7d}  "
              f"{restores:8d}  {error:.1e}")
    print(f"  wall per event: FMI 3.0 / FMI 2.0 = {walls['fmi3'] / walls['fmi2']:.2f}")


if __name__ == "__main__":
    main()
