"""Coupling accuracy against cost: error of two pendulum FMUs coupled by the torsion spring FMU
(examples/coupled_pendulums.py, Gauss-Seidel, 2 s) against the monolithic solution (solve_ivp,
rtol 1e-12), with its FMU doStep calls and wall time, measured side by side in one process:

- fixed steps with held inputs (the default), over dt;
- fixed steps with first- and second-order input derivatives (input_order 1, 2);
- error-controlled steps (StepControl, rtol = atol = TOL) with held inputs and with input
  derivatives, with rollback and without (non-iterative).

Then, for an error of at most 1e-6 (largest |theta error| over the run), the fewest doSteps each
way needs: held inputs on a fixed step are extrapolated from their first-order fit (the run
would take millions of steps; --held-dt runs one anyway), the others are the cheapest measured
row. Wall times are one run each (best of --repeat).

    python benchmarks/coupling_accuracy.py [--repeat 3] [--held-dt 1e-5]
"""

from __future__ import annotations

import argparse
import math
import platform
import time
from dataclasses import dataclass

import coupled_pendulums
import numpy as np
from syssimx import GaussSeidelAlgorithm, StepControl

TARGET = 1e-6


@dataclass
class Row:
    way: str
    setting: str
    worst: float
    final: float
    do_steps: int
    wall: float


def measure(way: str, setting: str, algorithm: GaussSeidelAlgorithm, dt: float,
            repeat: int) -> Row:
    best = math.inf
    for _ in range(repeat):
        system = coupled_pendulums.build(algorithm)
        system.initialize(0.0)
        start = time.perf_counter()
        result = system.run(0.0, coupled_pendulums.TF, dt)
        best = min(best, time.perf_counter() - start)
    t, p1 = result["P1"]
    _, p2 = result["P2"]
    reference = coupled_pendulums.monolithic(t)
    deviation = np.maximum(np.abs(p1["theta"] - reference[0]), np.abs(p2["theta"] - reference[1]))
    return Row(way, setting, float(deviation.max()), float(deviation[-1]),
               result.statistics.do_step_calls, best)


def rows(repeat: int, held_dt: float | None) -> list[Row]:
    found = []
    held_dts = [0.01, 0.001, 1e-4] + ([held_dt] if held_dt else [])
    for dt in held_dts:
        found.append(measure("fixed, held inputs", f"dt {dt:g}", GaussSeidelAlgorithm(), dt,
                             repeat))
    for order in (1, 2):
        for dt in (0.01, 0.005, 0.0025, 0.00125):
            found.append(measure(f"fixed, input order {order}", f"dt {dt:g}",
                                 GaussSeidelAlgorithm(input_order=order), dt, repeat))
    found.append(measure("adaptive, held inputs", "tol 1e-3", GaussSeidelAlgorithm(
        step_control=StepControl(rtol=1e-3, atol=1e-3)), 0.1, repeat))
    for order in (1, 2):
        for rollback in (True, False):
            for tol in (1e-3, 1e-5, 1e-7):
                if order == 1 and tol < 1e-6:
                    continue  # 60 000 doSteps: far beyond order 2 at the same error
                way = (f"adaptive{'' if rollback else ' non-iterative'}, input order {order}")
                control = StepControl(rtol=tol, atol=tol, rollback=rollback)
                found.append(measure(way, f"tol {tol:g}", GaussSeidelAlgorithm(
                    input_order=order, step_control=control), 0.1, repeat))
    return found


def held_do_steps_for(target: float, found: list[Row]) -> float:
    """doSteps a fixed step with held inputs needs for `target`: error = c * dt (first order),
    c from its finest measured row."""
    finest = min((r for r in found if r.way == "fixed, held inputs"),
                 key=lambda r: float(r.setting.split()[1]))
    return finest.do_steps * (finest.worst / target)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--held-dt", type=float, default=None,
                        help="also run held inputs on this fixed step")
    args = parser.parse_args()
    found = rows(args.repeat, args.held_dt)
    print(f"machine: {platform.machine()} {platform.processor() or ''}".rstrip())
    print(f"{'way':<40}{'setting':>12}{'max error':>12}{'end error':>12}{'doSteps':>10}"
          f"{'wall ms':>10}")
    for r in found:
        print(f"{r.way:<40}{r.setting:>12}{r.worst:>12.3g}{r.final:>12.3g}{r.do_steps:>10d}"
              f"{1e3 * r.wall:>10.1f}")
    print(f"\nfewest doSteps for a largest error <= {TARGET:g}:")
    held = held_do_steps_for(TARGET, found)
    print(f"  {'fixed, held inputs (first-order fit)':<48}{held:>12.3g}")
    best: dict[str, Row] = {}
    for r in found:
        kind = r.way.split(",")[0] + (", derivatives" if "order" in r.way else ", held")
        if r.worst <= TARGET and (kind not in best or r.do_steps < best[kind].do_steps):
            best[kind] = r
    for kind, r in best.items():
        print(f"  {kind + ': ' + r.way.split(', ', 1)[1] + ' ' + r.setting:<48}"
              f"{r.do_steps:>12d}  ({held / r.do_steps:.0f}x fewer than held fixed)")
    fixed = best.get("fixed, derivatives")
    adaptive = best.get("adaptive, derivatives")
    if fixed and adaptive:
        print(f"  adaptive + derivatives against fixed + derivatives: "
              f"{fixed.do_steps / adaptive.do_steps:.2f}x fewer doSteps")


if __name__ == "__main__":
    main()
