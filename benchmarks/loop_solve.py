"""Cost of solving an algebraic loop at every communication point.

A PI controller (feedthrough from its measurement) drives a gain whose output is the
measurement: an algebraic loop of two FMUs, solved by the engine at every communication point.
The same system with the loop broken by a delay (the gain declared without feedthrough, so
Gauss-Seidel hands the controller the gain's output of the previous point) is timed side by side.

Prints Newton iterations per step, the time per step of both variants, their ratio and the
overhead of the loop solve per step, and how far each variant is from the exact solution of the
continuous loop (u = ki * I / (1 + kp * k), I' = -k * u).

    python benchmarks/loop_solve.py [--steps N] [--repeats R]
"""

from __future__ import annotations

import argparse
import math
import time
from typing import Any

import numpy as np
from syssimx import Connection, FMUComponent, System, fmus

KP, KI, GAIN, INTEGRAL0 = 0.5, 1.0, 0.5, 1.0


def build(loop_solved: bool) -> System:
    controller = FMUComponent("PI", fmus.path("pi_controller"))
    controller.set_parameters(kp=KP, ki=KI, integral0=INTEGRAL0)
    gain = FMUComponent("Gain", fmus.path("gain"))
    gain.set_parameters(k=GAIN)
    if not loop_solved:
        gain.direct_feedthrough = {"y": set()}  # declared, hence respected: the loop is delayed
    system = System("loop" if loop_solved else "delayed")
    system.add_component(controller)
    system.add_component(gain)
    system.add_connection(Connection("PI", "u", "Gain", "u"))
    system.add_connection(Connection("Gain", "y", "PI", "measurement"))
    return system


def exact_control(t: np.ndarray) -> np.ndarray:
    rate = GAIN * KI / (1.0 + KP * GAIN)
    return KI * INTEGRAL0 * np.exp(-rate * t) / (1.0 + KP * GAIN)


def timed_run(loop_solved: bool, tf: float, dt: float) -> tuple[float, System, Any]:
    """Seconds of ``run`` alone, and the system with its result (kept together: the result's
    arrays live in the system's engine)."""
    system = build(loop_solved)
    system.initialize(0.0)
    start = time.perf_counter()
    result = system.run(0.0, tf, dt)
    return time.perf_counter() - start, system, result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=int, default=20_000)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    dt = 1e-3
    tf = args.steps * dt

    best = {True: math.inf, False: math.inf}
    results: dict[bool, tuple[System, Any]] = {}
    for _ in range(args.repeats):  # alternate, so both variants see the same machine load
        for loop_solved in (True, False):
            seconds, system, result = timed_run(loop_solved, tf, dt)
            best[loop_solved] = min(best[loop_solved], seconds)
            results[loop_solved] = system, result

    stats = results[True][1].statistics
    print(f"PI controller + gain, {args.steps} steps of {dt} s, best of {args.repeats} runs")
    print(f"loop solves: {stats.loop_solves} ({stats.loop_solves / args.steps:.3f} per step), "
          f"Newton iterations: {stats.loop_iterations} "
          f"({stats.loop_iterations / max(stats.loop_solves, 1):.3f} per solve)")
    print("| variant | us per step | abs error of u at t0 | max abs error of u after t0 |")
    print("|---|---|---|---|")
    for loop_solved, label in ((True, "loop solved"), (False, "loop delayed")):
        t, values = results[loop_solved][1]["PI"]
        error = np.abs(values["u"] - exact_control(t))
        print(f"| {label} | {best[loop_solved] / args.steps * 1e6:.2f} | {error[0]:.2e} "
              f"| {float(np.max(error[1:])):.2e} |")
    overhead = (best[True] - best[False]) / args.steps * 1e6
    print(f"ratio solved/delayed: {best[True] / best[False]:.2f}; "
          f"loop-solve overhead: {overhead:.2f} us per step")


if __name__ == "__main__":
    main()
