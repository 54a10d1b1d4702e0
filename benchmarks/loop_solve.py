"""Cost of solving an algebraic loop at every communication point.

A PI controller (feedthrough from its measurement) drives a gain whose output is the
measurement: an algebraic loop of two FMUs, solved by the engine at every communication point,
with Newton's Jacobian from fmi2GetDirectionalDerivative (both FMUs provide it) or from finite
differences. The same system with the loop broken by a delay (the gain declared without
feedthrough, so Gauss-Seidel hands the controller the gain's output of the previous point) is
timed side by side.

Prints Newton iterations per solve and the time per step of each variant, the overhead of the
loop solve per step against the delayed loop, and how far each variant is from the exact
solution of the continuous loop (u = ki * I / (1 + kp * k), I' = -k * u).

    python benchmarks/loop_solve.py [--steps N] [--repeats R]
"""

from __future__ import annotations

import argparse
import math
import time
from typing import Any

import numpy as np
from syssimx import Connection, FMUComponent, GaussSeidelAlgorithm, System, fmus

KP, KI, GAIN, INTEGRAL0 = 0.5, 1.0, 0.5, 1.0
# variant -> the loop's Jacobian, or None when the loop is broken by a delay
VARIANTS = {"loop solved, directional derivatives": "auto",
            "loop solved, finite differences": "finite_differences",
            "loop delayed": None}


def build(loop_jacobian: str | None) -> System:
    loop_solved = loop_jacobian is not None
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
    system.set_algorithm(GaussSeidelAlgorithm(loop_jacobian=loop_jacobian or "auto"))
    return system


def exact_control(t: np.ndarray) -> np.ndarray:
    rate = GAIN * KI / (1.0 + KP * GAIN)
    return KI * INTEGRAL0 * np.exp(-rate * t) / (1.0 + KP * GAIN)


def timed_run(loop_jacobian: str | None, tf: float, dt: float) -> tuple[float, System, Any]:
    """Seconds of ``run`` alone, and the system with its result (kept together: the result's
    arrays live in the system's engine)."""
    system = build(loop_jacobian)
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

    best = dict.fromkeys(VARIANTS, math.inf)
    results: dict[str, tuple[System, Any]] = {}
    for _ in range(args.repeats):  # interleaved, so every variant sees the same machine load
        for label, loop_jacobian in VARIANTS.items():
            seconds, system, result = timed_run(loop_jacobian, tf, dt)
            best[label] = min(best[label], seconds)
            results[label] = system, result

    print(f"PI controller + gain, {args.steps} steps of {dt} s, best of {args.repeats} runs")
    print("| variant | us per step | loop solves per step | Newton iterations per solve "
          "| directional derivatives per solve | abs error of u at t0 "
          "| max abs error of u after t0 |")
    print("|---|---|---|---|---|---|---|")
    for label in VARIANTS:
        result = results[label][1]
        stats = result.statistics
        solves = max(stats.loop_solves, 1)
        t, values = result["PI"]
        error = np.abs(values["u"] - exact_control(t))
        print(f"| {label} | {best[label] / args.steps * 1e6:.2f} "
              f"| {stats.loop_solves / args.steps:.3f} | {stats.loop_iterations / solves:.3f} "
              f"| {stats.directional_derivatives / solves:.3f} | {error[0]:.2e} "
              f"| {float(np.max(error[1:])):.2e} |")
    delayed = best["loop delayed"]
    for label in list(VARIANTS)[:2]:
        print(f"{label}: ratio to delayed {best[label] / delayed:.2f}, loop-solve overhead "
              f"{(best[label] - delayed) / args.steps * 1e6:.2f} us per step")


if __name__ == "__main__":
    main()
