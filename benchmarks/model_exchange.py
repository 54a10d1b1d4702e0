"""Model Exchange in the engine: the same Reference FMUs run as Co-Simulation (their own
fixed-step Euler behind fmi2DoStep) and as Model Exchange (integrated by the engine with CVODE,
events found by root finding), and FMPy's Model Exchange simulation (simulate_fmu with
fmi_type="ModelExchange", solver="CVode") on the same grid and tolerance. Measured side by side
in one run, median of --repeat:

  BouncingBall  restitution 0.9 (36 bounces, then it rests), 9 s in steps of 10 ms
  VanDerPol     20 s in steps of 10 ms, no events

Printed per model and run: wall time, microseconds per communication step (the cost of one
doStep of the component), the events handled and events per second of wall time, the largest
error of the first state against an accurate solution (closed form; VanDerPol: scipy's DOP853
at 1e-13), and the ratios to syssimx's Model Exchange run.

    python benchmarks/model_exchange.py [--repeat N] [--tolerance RTOL]

The Reference FMUs are found through SYSSIMX_REFERENCE_FMUS or at <repository>/../shared/
reference-fmus.
"""

from __future__ import annotations

import argparse
import gc
import os
import statistics
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from fmpy import simulate_fmu
from scipy.integrate import solve_ivp
from syssimx import FMUComponent, System

DT = 0.01
G, RESTITUTION, V_MIN = 9.81, 0.9, 0.1
MODELS = {"BouncingBall": 9.0, "VanDerPol": 20.0}


def reference_folder() -> Path:
    given = os.environ.get("SYSSIMX_REFERENCE_FMUS")
    root = Path(given) if given else Path(__file__).resolve().parents[1].parent / "shared" / \
        "reference-fmus"
    return root / "fmi2"


def ball_height(t: np.ndarray) -> np.ndarray:
    """The closed-form height: bounces with RESTITUTION until the rebound is below V_MIN."""
    h = np.zeros_like(t)
    start, speed, height = 0.0, 0.0, 1.0
    while True:
        land = start + (speed + np.sqrt(speed**2 + 2 * G * height)) / G
        flight = (t >= start) & (t < land)
        s = t[flight] - start
        h[flight] = height + speed * s - G * s**2 / 2
        speed, start, height = RESTITUTION * (G * (land - start) - speed), land, 0.0
        if speed < V_MIN:
            return h


def accurate(model: str, t: np.ndarray) -> np.ndarray:
    if model == "BouncingBall":
        return ball_height(t)
    solution = solve_ivp(lambda _, x: [x[1], (1 - x[0] ** 2) * x[1] - x[0]], (0.0, t[-1]),
                         [2.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-13, t_eval=t)
    return solution.y[0]


def first_state(model: str) -> str:
    return "h" if model == "BouncingBall" else "x0"


def syssimx_run(path: Path, model: str, interface: str, tolerance: float
                ) -> Callable[[], tuple[np.ndarray, int]]:
    def run() -> tuple[np.ndarray, int]:
        component = FMUComponent("M", path, interface=interface, tolerance=tolerance)
        if model == "BouncingBall":
            component.set_parameters(e=RESTITUTION)
        system = System(model)
        system.add_component(component)
        system.initialize(0.0)
        result = system.run(0.0, MODELS[model], DT)
        events = result.statistics.own_events
        return result["M"][1][first_state(model)].copy(), events
    return run


def fmpy_run(path: Path, model: str, tolerance: float) -> Callable[[], tuple[np.ndarray, int]]:
    def run() -> tuple[np.ndarray, int]:
        starts = {"e": RESTITUTION} if model == "BouncingBall" else {}
        with_events = simulate_fmu(path, fmi_type="ModelExchange", solver="CVode",
                                   relative_tolerance=tolerance, stop_time=MODELS[model],
                                   output_interval=DT, start_values=starts,
                                   output=[first_state(model)])
        # record_events adds a sample before and after each event: those are the events
        grid = np.isclose(with_events["time"] / DT, np.round(with_events["time"] / DT),
                          rtol=0, atol=1e-6)
        _, first = np.unique(with_events["time"], return_index=True)
        on_grid = np.zeros(len(grid), dtype=bool)
        on_grid[first] = grid[first]
        events = int((len(with_events) - int(on_grid.sum())) // 2)
        return with_events[first_state(model)][on_grid], events
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
    folder = reference_folder()
    if not folder.is_dir():
        raise SystemExit(f"the Reference FMUs are not in {folder}: set SYSSIMX_REFERENCE_FMUS")
    print(f"relative tolerance {args.tolerance:g}, step {DT} s, median of {args.repeat}")
    for model, stop in MODELS.items():
        path = folder / f"{model}.fmu"
        steps = round(stop / DT)
        runs = {
            "syssimx Co-Simulation (FMU's Euler)": syssimx_run(path, model, "co-simulation",
                                                                args.tolerance),
            "syssimx Model Exchange (CVODE)": syssimx_run(path, model, "model-exchange",
                                                           args.tolerance),
            "FMPy Model Exchange (CVode)": fmpy_run(path, model, args.tolerance),
        }
        measured = {name: measure(run, args.repeat) for name, run in runs.items()}
        base = measured["syssimx Model Exchange (CVODE)"][0]
        print(f"\n{model}: {stop:g} s, {steps} communication steps")
        print(f"  {'run':<38}{'wall s':>9}{'us/step':>9}{'events':>8}{'events/s':>10}"
              f"{'max error':>11}{'x ME':>7}")
        for name, (seconds, values, events) in measured.items():
            t = np.arange(len(values)) * DT
            error = float(np.max(np.abs(values - accurate(model, t))))
            rate = f"{events / seconds:>10.0f}" if events else f"{'-':>10}"
            print(f"  {name:<38}{seconds:>9.4f}{seconds / steps * 1e6:>9.1f}{events:>8}"
                  f"{rate}{error:>11.2e}{seconds / base:>7.2f}")


if __name__ == "__main__":
    main()
