"""What an event costs the master: the seed scenario (pendulum against a wall, dt 0.05,
tol_time 1e-9) over `--stop` seconds, its handler written three ways, in one run:

  python        the seed's handler: a Python function calling component.reinitialize with
                the outputs' magnitudes (examples/pendulum_wall.py: bounce)
  declarative   Reinitialize(theta0="theta", omega0="-omega"): run by the engine, no Python
  no events     the same FMU and steps without the wall (plain Gauss-Seidel): the baseline

Per event: (the run's CPU time - the baseline's) / events, which counts the localization
(restores and trial steps), the handler and the restart of the FMU. CPU time of this process,
not wall time: on a shared machine the wall counts the other processes' turns too. Both
handlers give the same event times and samples (checked). Median of `--repeats`.

    python benchmarks/event_handler.py [--stop 30] [--repeats 5]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
import pendulum_wall
from syssimx import (
    EventConnection,
    FMUComponent,
    HybridAlgorithm,
    Reinitialize,
    System,
    fmus,
)

DT = 0.05


def build(solver: str, handler: Callable[..., None] | None) -> System:
    pendulum = FMUComponent("P", fmus.path(f"pendulum_{solver}"))
    pendulum.set_parameters(theta0=0.5, omega0=0.0)
    if solver == "cvode":
        pendulum.set_parameters(cvode_relative_tolerance=1e-10)
    system = System("wall")
    system.add_component(pendulum)
    if handler is not None:
        pendulum.add_event_indicator("wall_hit", variable="theta", direction=-1)
        pendulum.add_event_handler("omega_invert", handler)
        system.add_event_connection(EventConnection("P", "wall_hit", "P", "omega_invert"))
        system.set_algorithm(HybridAlgorithm(tol_time=1e-9, tol_value=1e-9))
    return system


def timed(system: System, stop: float, repeats: int) -> tuple[float, Any]:
    walls = []
    for _ in range(repeats):
        system.initialize(0.0)
        start = time.process_time()
        result = system.run(0.0, stop, DT)
        walls.append(time.process_time() - start)
    return statistics.median(walls), result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--stop", type=float, default=30.0)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    print(f"seed scenario over {args.stop} s, dt {DT}, median of {args.repeats}")
    print(f"{'FMU':<16}{'handler':<13}{'events':>7}{'CPU ms':>9}{'us/event':>10}")
    for solver in ("euler", "cvode"):
        baseline, _ = timed(build(solver, None), args.stop, args.repeats)
        results = {}
        for name, handler in (("python", pendulum_wall.bounce),
                              ("declarative", Reinitialize(theta0="theta", omega0="-omega"))):
            wall, result = timed(build(solver, handler), args.stop, args.repeats)
            events = len(result.events)
            results[name] = ([e.t for e in result.events], result["P"][1]["theta"])
            print(f"{'pendulum_' + solver:<16}{name:<13}{events:>7}{wall * 1e3:>9.2f}"
                  f"{(wall - baseline) / events * 1e6:>10.1f}")
        print(f"{'pendulum_' + solver:<16}{'no events':<13}{0:>7}{baseline * 1e3:>9.2f}")
        same = results["python"][0] == results["declarative"][0] and np.array_equal(
            results["python"][1], results["declarative"][1])
        print(f"{'':<16}the two handlers' event times and samples identical: {same}")


if __name__ == "__main__":
    main()
