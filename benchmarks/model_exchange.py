"""Model Exchange in the engine: the same FMUs run as Co-Simulation (behind fmi2DoStep) and as
Model Exchange (integrated by the engine with CVODE, events found by root finding), and FMPy's
Model Exchange simulation (simulate_fmu with fmi_type="ModelExchange", solver="CVode") on the
same grid and tolerance; the same models' FMI 3.0 builds as Model Exchange too (our
`<stem>_fmi3`, the Reference FMUs' fmi3/ folder), through the same engine component. Measured
side by side in one run, median of --repeat:

  bouncing_ball_cvode  ours, CS with its own CVODE and root finding: restitution 0.8 (31
                       bounces, then it rests at 4.06 s), 4 s in steps of 10 ms
  pendulum_cvode       ours, CS with its own CVODE: 10 s in steps of 10 ms, no events
  BouncingBall         the Reference FMU, CS with a fixed-step Euler: restitution 0.9 (36
                       bounces, then it rests), 9 s in steps of 10 ms
  VanDerPol            the Reference FMU, CS with a fixed-step Euler: 20 s, no events

Printed per model and run: wall time, microseconds per communication step (the cost of one
doStep of the component), the events handled and events per second of wall time, the largest
error of the first state against an accurate solution (closed form; the pendulums: scipy's
DOP853 at 1e-13), and the ratios to syssimx's Model Exchange run.

    python benchmarks/model_exchange.py [--repeat N] [--tolerance RTOL]

The Reference FMUs are found through SYSSIMX_REFERENCE_FMUS or at <repository>/../shared/
reference-fmus; without them only our FMUs run.
"""

from __future__ import annotations

import argparse
import gc
import os
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from fmpy import simulate_fmu
from scipy.integrate import solve_ivp
from syssimx import FMUComponent, System, fmus

DT = 0.01
G = 9.81


@dataclass(frozen=True)
class Case:
    model: str
    stop: float
    state: str  # the state compared with the accurate solution
    parameters: dict[str, float]
    accurate: Callable[[np.ndarray], np.ndarray]
    reference: bool  # a Reference FMU (else one of ours)

    def path(self, fmi3: bool = False) -> Path:
        if self.reference:
            return reference_folder(fmi3) / f"{self.model}.fmu"
        return fmus.path(self.model + "_fmi3" if fmi3 else self.model)


def reference_folder(fmi3: bool = False) -> Path:
    given = os.environ.get("SYSSIMX_REFERENCE_FMUS")
    root = Path(given) if given else Path(__file__).resolve().parents[1].parent / "shared" / \
        "reference-fmus"
    return root / ("fmi3" if fmi3 else "fmi2")


def ball_height(restitution: float, resting: Callable[[float], bool]) -> Callable[
        [np.ndarray], np.ndarray]:
    """The closed-form height from 1 m: bounces with `restitution` until resting(rebound)."""
    def height_at(t: np.ndarray) -> np.ndarray:
        h = np.zeros_like(t)
        start, speed, height = 0.0, 0.0, 1.0
        while True:
            land = start + (speed + np.sqrt(speed**2 + 2 * G * height)) / G
            flight = (t >= start) & (t < land)
            s = t[flight] - start
            h[flight] = height + speed * s - G * s**2 / 2
            speed, start, height = restitution * (G * (land - start) - speed), land, 0.0
            if resting(speed):
                return h
    return height_at


def pendulum(t: np.ndarray) -> np.ndarray:
    """pendulum_cvode from 0.5 rad at rest (m 40 kg, L 0.6 m, I 20 kg m2)."""
    omega2 = 40.0 * G * 0.6 / 20.0
    return solve_ivp(lambda _, y: [y[1], -omega2 * np.sin(y[0])], (0.0, t[-1]), [0.5, 0.0],
                     method="DOP853", rtol=1e-13, atol=1e-13, t_eval=t).y[0]


def van_der_pol(t: np.ndarray) -> np.ndarray:
    return solve_ivp(lambda _, x: [x[1], (1 - x[0] ** 2) * x[1] - x[0]], (0.0, t[-1]),
                     [2.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-13, t_eval=t).y[0]


CASES = [
    Case("bouncing_ball_cvode", 4.0, "h", {"e": 0.8},
         ball_height(0.8, lambda v: v**2 <= 2 * G * 1e-6), reference=False),
    Case("pendulum_cvode", 10.0, "theta", {"theta0": 0.5}, pendulum, reference=False),
    Case("BouncingBall", 9.0, "h", {"e": 0.9}, ball_height(0.9, lambda v: v < 0.1),
         reference=True),
    Case("VanDerPol", 20.0, "x0", {}, van_der_pol, reference=True),
]


def syssimx_run(case: Case, interface: str, tolerance: float, fmi3: bool = False
                ) -> Callable[[], tuple[np.ndarray, int]]:
    def run() -> tuple[np.ndarray, int]:
        component = FMUComponent("M", case.path(fmi3), interface=interface, tolerance=tolerance)
        component.set_parameters(**case.parameters)
        if "cvode_relative_tolerance" in component.parameters:  # our CS build's own CVODE
            component.set_parameters(cvode_relative_tolerance=tolerance)
        system = System(case.model)
        system.add_component(component)
        system.initialize(0.0)
        result = system.run(0.0, case.stop, DT)
        return result["M"][1][case.state].copy(), result.statistics.own_events
    return run


def fmpy_run(case: Case, tolerance: float) -> Callable[[], tuple[np.ndarray, int]]:
    def run() -> tuple[np.ndarray, int]:
        with_events = simulate_fmu(case.path(), fmi_type="ModelExchange", solver="CVode",
                                   relative_tolerance=tolerance, stop_time=case.stop,
                                   output_interval=DT, start_values=case.parameters,
                                   output=[case.state])
        # record_events adds a sample before and after each event: those are the events
        grid = np.isclose(with_events["time"] / DT, np.round(with_events["time"] / DT),
                          rtol=0, atol=1e-6)
        _, first = np.unique(with_events["time"], return_index=True)
        on_grid = np.zeros(len(grid), dtype=bool)
        on_grid[first] = grid[first]
        events = int((len(with_events) - int(on_grid.sum())) // 2)
        return with_events[case.state][on_grid], events
    return run


def measure(run: Callable[[], tuple[np.ndarray, int]], repeat: int
            ) -> tuple[float, np.ndarray, int]:
    times, values, events = [], np.empty(0), 0
    for _ in range(repeat):
        gc.collect()
        start = time.perf_counter()
        values, events = run()
        times.append(time.perf_counter() - start)
    return statistics.median(times), values, events


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--tolerance", type=float, default=1e-6)
    args = parser.parse_args()
    print(f"relative tolerance {args.tolerance:g}, step {DT} s, median of {args.repeat}")
    for case in CASES:
        if case.reference and not reference_folder().is_dir():
            print(f"\n{case.model}: skipped (no Reference FMUs in {reference_folder()}: set "
                  "SYSSIMX_REFERENCE_FMUS)")
            continue
        steps = round(case.stop / DT)
        runs = {
            "syssimx Co-Simulation (FMU's solver)": syssimx_run(case, "co-simulation",
                                                                 args.tolerance),
            "syssimx Model Exchange (CVODE)": syssimx_run(case, "model-exchange",
                                                           args.tolerance),
            "syssimx FMI 3.0 Model Exchange": syssimx_run(case, "model-exchange",
                                                           args.tolerance, fmi3=True),
            "FMPy Model Exchange (CVode)": fmpy_run(case, args.tolerance),
        }
        measured = {name: measure(run, args.repeat) for name, run in runs.items()}
        base = measured["syssimx Model Exchange (CVODE)"][0]
        print(f"\n{case.model}: {case.stop:g} s, {steps} communication steps")
        print(f"  {'run':<38}{'wall s':>9}{'us/step':>9}{'events':>8}{'events/s':>10}"
              f"{'max error':>11}{'x ME':>7}")
        for name, (seconds, values, events) in measured.items():
            t = np.arange(len(values)) * DT
            error = float(np.max(np.abs(values - case.accurate(t))))
            rate = f"{events / seconds:>10.0f}" if events else f"{'-':>10}"
            print(f"  {name:<38}{seconds:>9.4f}{seconds / steps * 1e6:>9.1f}{events:>8}"
                  f"{rate}{error:>11.2e}{seconds / base:>7.2f}")


if __name__ == "__main__":
    main()
