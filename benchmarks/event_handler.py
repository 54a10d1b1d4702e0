"""What an event costs the master: the seed scenario (pendulum against a wall, dt 0.05,
tol_time 1e-9) over `--stop` seconds, its handler written three ways, in one run:

  python        the seed's handler: a Python function calling component.reinitialize with
                the outputs' magnitudes (examples/pendulum_wall.py: bounce)
  declarative   Reinitialize(theta0="theta", omega0="-omega"): run by the engine, no Python
  no events     the same FMU and steps without the wall (plain Gauss-Seidel): the baseline

Per event: (the run's CPU time - the baseline's) / events, which counts the localization
(restores and trial steps), the handler, the restart of the FMU and reading the event records
into Python. CPU time of this process, not wall time: on a shared machine the wall counts the
other processes' turns too. The three runs take turns within each repeat, and the per-event
figure is the median over the repeats of each repeat's difference, so that a slow spell of the
machine weighs on both sides of a difference. Both handlers give the same event times and
samples (checked).

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


def timed(systems: dict[str, System], stop: float, repeats: int
          ) -> tuple[dict[str, list[float]], dict[str, Any]]:
    """Each system's run CPU times, the systems taking turns within each repeat, and their
    last results."""
    times: dict[str, list[float]] = {name: [] for name in systems}
    results: dict[str, Any] = {}
    for _ in range(repeats):
        for name, system in systems.items():
            system.initialize(0.0)
            start = time.process_time()
            results[name] = system.run(0.0, stop, DT)
            times[name].append(time.process_time() - start)
    return times, results


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--stop", type=float, default=30.0)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    print(f"seed scenario over {args.stop} s, dt {DT}, median of {args.repeats}")
    print(f"{'FMU':<16}{'handler':<13}{'events':>7}{'CPU ms':>9}{'us/event':>10}")
    for solver in ("euler", "cvode"):
        times, results = timed(
            {"no events": build(solver, None),
             "python": build(solver, pendulum_wall.bounce),
             "declarative": build(solver, Reinitialize(theta0="theta", omega0="-omega"))},
            args.stop, args.repeats)
        baseline = times["no events"]
        for name in ("python", "declarative"):
            events = len(results[name].events)
            per_event = statistics.median(
                (run - base) / events for run, base in zip(times[name], baseline, strict=True))
            print(f"{'pendulum_' + solver:<16}{name:<13}{events:>7}"
                  f"{statistics.median(times[name]) * 1e3:>9.2f}{per_event * 1e6:>10.1f}")
        print(f"{'pendulum_' + solver:<16}{'no events':<13}{0:>7}"
              f"{statistics.median(baseline) * 1e3:>9.2f}")
        python, declarative = results["python"], results["declarative"]
        same = [e.t for e in python.events] == [e.t for e in declarative.events] and \
            np.array_equal(python["P"][1]["theta"], declarative["P"][1]["theta"])
        print(f"{'':<16}the two handlers' event times and samples identical: {same}")


if __name__ == "__main__":
    main()
