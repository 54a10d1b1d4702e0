"""What isolation costs: the same System run with its FMU in process and isolated (the binary in
a host process, every fmi2 call over a socket), side by side in one run.

  grid       one FMU, no events, 10 000 steps of dt 1e-3 (pendulum_euler: 10 Euler substeps
             per doStep; pendulum_cvode at its default tolerance)
  seed       the seed scenario (examples/pendulum_wall.py, CVODE FMU): 3 s, dt 0.05, three wall
             hits located by rollback, so fmi2Get/SetFMUstate cross the socket too

For each case: the wall time per macro step in process and isolated (median of --repeat runs,
the two alternating), their ratio, the time isolation adds per doStep and per fmi2 call (the
FMU's counters give the calls per run), and whether the results are bit-identical.

    python benchmarks/isolation_cost.py [--repeat N]
"""

from __future__ import annotations

import argparse
import functools
import gc
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from syssimx import FMUComponent, System, fmus

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
GRID_STEPS, GRID_DT = 10_000, 1e-3

Run = tuple[float, int, int, int, np.ndarray]  # wall, macro steps, doSteps, fmi2 calls, theta


def grid_run(fmu: str, isolated: bool) -> Run:
    pendulum = FMUComponent("P", fmus.path(fmu), isolated=isolated)
    pendulum.set_parameters(theta0=0.5, omega0=0.0)
    system = System("grid")
    system.add_component(pendulum)
    system.initialize(0.0)
    before = pendulum.instance.counters()
    start = time.perf_counter()
    result = system.run(0.0, GRID_STEPS * GRID_DT, GRID_DT)
    wall = time.perf_counter() - start
    return measured(wall, result.statistics.macro_steps, before, pendulum,
                    result["P"][1]["theta"])


def seed_run(isolated: bool) -> Run:
    sys.path.insert(0, str(EXAMPLES))
    import pendulum_wall

    pendulum_wall.FMUComponent = functools.partial(FMUComponent, isolated=isolated)
    system, pendulum = pendulum_wall.build("cvode")
    before = pendulum.instance.counters()
    start = time.perf_counter()
    result = system.run(0.0, 3.0, 0.05)
    wall = time.perf_counter() - start
    return measured(wall, result.statistics.macro_steps, before, pendulum,
                    np.array([event.t for event in result.events]))


def measured(wall: float, macro_steps: int, before: dict[str, int], pendulum: FMUComponent,
             values: np.ndarray) -> Run:
    after = pendulum.instance.counters()
    calls = sum(after[k] - before[k] for k in ("do_step", "get_state", "set_state",
                                               "get_values", "set_values"))
    outcome = (wall, macro_steps, after["do_step"] - before["do_step"], calls, values.copy())
    pendulum.free()
    return outcome


def compare(name: str, run: Callable[[bool], Run], repeat: int) -> None:
    walls: dict[bool, list[float]] = {False: [], True: []}
    last: dict[bool, Run] = {}
    for _ in range(repeat):
        for isolated in (False, True):
            gc.collect()
            last[isolated] = run(isolated)
            walls[isolated].append(last[isolated][0])
    here, there = statistics.median(walls[False]), statistics.median(walls[True])
    _, steps, do_steps, calls, values = last[True]
    identical = np.array_equal(last[False][4], values) and last[False][1:4] == last[True][1:4]
    print(f"{name}: {steps} macro steps, {do_steps} doStep, {calls} fmi2 calls per run")
    print(f"  in process {here / steps * 1e6:8.2f} us per step   isolated "
          f"{there / steps * 1e6:8.2f} us per step   ratio {there / here:5.1f}")
    print(f"  isolation adds {(there - here) / do_steps * 1e6:.2f} us per doStep, "
          f"{(there - here) / calls * 1e6:.2f} us per fmi2 call; "
          f"results bit-identical: {'yes' if identical else 'NO'}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    compare("grid, pendulum_euler, dt 1e-3", functools.partial(grid_run, "pendulum_euler"),
            args.repeat)
    compare("grid, pendulum_cvode, dt 1e-3", functools.partial(grid_run, "pendulum_cvode"),
            args.repeat)
    compare("seed scenario, pendulum_cvode, 3 s, 3 events", seed_run, args.repeat)


if __name__ == "__main__":
    main()
