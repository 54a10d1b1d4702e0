"""What an event costs the master: the seed scenario (pendulum against a wall, dt 0.05,
tol_time 1e-9) over `--stop` seconds, its handler written two ways, against the same FMU
without the wall:

  python        the seed's handler: a Python function calling component.reinitialize with
                the outputs' magnitudes (examples/pendulum_wall.py: bounce)
  declarative   Reinitialize(theta0="theta", omega0="-omega"): run by the engine, no Python
  no events     the same FMU and steps without the wall (plain Gauss-Seidel): the baseline

Per event: what a run with events costs beyond the run without them, divided by its events;
that counts the localization (restores and trial steps), the handler, the restart of the FMU
and reading the event records into Python. CPU time of this process, not wall time: on a
shared machine the wall counts the other processes' turns too. The three runs take turns
within each repeat (each repeat starting with the next of them, so that none always runs after
the same one). A 2-core VM shared with other work slows a whole run by 20-30 % at times
(the other process on the sibling core), which swamps a difference of a few per cent: the
figure is therefore the ratio of each repeat's run to its own run without events, priced at
the fastest run without events, (ratio - 1) * fastest / events, so that a slow spell weighs
on both runs of a ratio. The table prints its median and range over the repeats, and the
plain difference (run - run without events) / events as a median too. A run makes its event
records (Python objects) only when they are first asked for: `read` is that first reading of
`result.events`, per event, timed apart from the run. Both handlers give the
same event times and samples (checked). The FMU calls per event come from the run's
statistics: doStep calls and state restores beyond the run without events.

With --builds, each round runs every meson build directory (SYSSIMX_BUILD_DIR, with the Python
package of the source tree it was built from) in a fresh process, the builds in turn, so that
two versions (one kept aside and the current one) are compared in one run; the figures pool
the repeats of every round.

    python benchmarks/event_handler.py [--stop 300] [--repeats 11] [--rounds 1]
                                       [--builds build/before,build/dev] [--solvers euler]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from syssimx import System

DT = 0.05
SOLVERS = ("euler", "cvode")
HANDLERS = ("python", "declarative")


def build(solver: str, handler: Callable[..., None] | Any | None) -> System:
    # imported here: with --builds this process only starts others, each on its own engine
    from syssimx import EventConnection, FMUComponent, HybridAlgorithm, System, fmus

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


def measure(stop: float, repeats: int, solvers: list[str]) -> dict[str, Any]:
    """Per solver and handler: the CPU time of each repeat's run (s), the event count and the
    FMU calls per event; per solver the runs without events and whether the two handlers
    agree."""
    import numpy as np

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
    import pendulum_wall
    from syssimx import Reinitialize

    report: dict[str, Any] = {}
    for solver in solvers:
        systems = {"no events": build(solver, None),
                   "python": build(solver, pendulum_wall.bounce),
                   "declarative": build(solver, Reinitialize(theta0="theta", omega0="-omega"))}
        times: dict[str, list[float]] = {name: [] for name in systems}
        reading: dict[str, list[float]] = {name: [] for name in systems}
        results: dict[str, Any] = {}
        for system in systems.values():  # a first run untimed, over the first event
            system.initialize(0.0)
            system.run(0.0, 1.0, DT)
        names = list(systems)
        for repeat in range(repeats):
            # each repeat starts with another run: none always follows the same one
            for name in names[repeat % 3:] + names[:repeat % 3]:
                system = systems[name]
                system.initialize(0.0)
                start = time.process_time()
                results[name] = system.run(0.0, stop, DT)
                times[name].append(time.process_time() - start)
                # the records are made when first asked for: timed apart
                start = time.process_time()
                events = len(results[name].events)
                reading[name].append((time.process_time() - start) / max(events, 1))
        base = results["no events"].statistics
        for name in HANDLERS:
            events = len(results[name].events)
            calls = results[name].statistics
            report[f"{solver} {name}"] = {
                "events": events,
                "run": times[name],
                "read": reading[name],
                "do_steps": (calls.do_step_calls - base.do_step_calls) / events,
                "restores": (calls.state_restores - base.state_restores) / events,
            }
        report[f"{solver} no events"] = {"run": times["no events"]}
        python, declarative = results["python"], results["declarative"]
        report[f"{solver} identical"] = (
            [e.t for e in python.events] == [e.t for e in declarative.events]
            and bool(np.array_equal(python["P"][1]["theta"], declarative["P"][1]["theta"])))
    return report


def measure_in(build_dir: str, stop: float, repeats: int, solvers: list[str]) -> dict[str, Any]:
    """measure() in a fresh process on the engine and FMUs of a meson build directory and the
    Python package of the source tree it was built from."""
    build = Path(build_dir).resolve()
    info = json.loads((build / "meson-info" / "meson-info.json").read_text())
    source = Path(info["directories"]["source"])
    env = dict(os.environ, SYSSIMX_BUILD_DIR=str(build), PYTHONPATH=str(source / "python"))
    out = subprocess.run(
        [sys.executable, __file__, "--child", "--stop", str(stop), "--repeats", str(repeats),
         "--solvers", ",".join(solvers)],
        env=env, check=True, capture_output=True, text=True).stdout
    return json.loads(out.splitlines()[-1])


def pooled(reports: list[dict[str, Any]], key: str, field: str = "run") -> list[float]:
    return [value for report in reports for value in report[key][field]]


def per_event(reports: list[dict[str, Any]], solver: str, handler: str
              ) -> tuple[list[float], list[float]]:
    """The per-event cost of every repeat (µs): from the ratio to the run without events,
    priced at the fastest of those, and the plain difference."""
    runs = pooled(reports, f"{solver} {handler}")
    free = pooled(reports, f"{solver} no events")
    events = reports[0][f"{solver} {handler}"]["events"]
    fastest = min(free)
    ratio = [(run / base - 1.0) * fastest / events * 1e6 for run, base in zip(runs, free,
                                                                               strict=True)]
    difference = [(run - base) / events * 1e6 for run, base in zip(runs, free, strict=True)]
    return ratio, difference


def print_table(name: str, reports: list[dict[str, Any]], solvers: list[str]) -> None:
    print(f"{name}:" if name else "")
    print(f"{'FMU':<16}{'handler':<13}{'events':>7}{'run ms':>9}{'us/event':>10}"
          f"{'range':>15}{'difference':>12}{'read':>7}{'doSteps':>9}{'restores':>9}")
    for solver in solvers:
        for handler in HANDLERS:
            first = reports[0][f"{solver} {handler}"]
            ratio, difference = per_event(reports, solver, handler)
            print(f"{'pendulum_' + solver:<16}{handler:<13}{first['events']:>7}"
                  f"{statistics.median(pooled(reports, f'{solver} {handler}')) * 1e3:>9.2f}"
                  f"{statistics.median(ratio):>10.1f}"
                  f"{f'{min(ratio):.1f}-{max(ratio):.1f}':>15}"
                  f"{statistics.median(difference):>12.1f}"
                  f"{statistics.median(pooled(reports, f'{solver} {handler}', 'read')) * 1e6:>7.1f}"
                  f"{first['do_steps']:>9.2f}{first['restores']:>9.2f}")
        free = pooled(reports, f"{solver} no events")
        same = all(report[f"{solver} identical"] for report in reports)
        print(f"{'pendulum_' + solver:<16}{'no events':<13}{0:>7}"
              f"{statistics.median(free) * 1e3:>9.2f}   (fastest {min(free) * 1e3:.2f})")
        print(f"{'':<16}the two handlers' event times and samples identical: {same}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--stop", type=float, default=300.0)
    parser.add_argument("--repeats", type=int, default=11)
    parser.add_argument("--rounds", type=int, default=1,
                        help="with --builds: how many times each build runs, in turns")
    parser.add_argument("--builds", help="meson build directories to compare, comma-separated")
    parser.add_argument("--solvers", default=",".join(SOLVERS),
                        help="the pendulum FMUs to run, comma-separated: euler, cvode")
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    solvers = args.solvers.split(",")
    if not set(solvers) <= set(SOLVERS):
        parser.error(f"--solvers: choose among {', '.join(SOLVERS)}")
    if args.child:
        print(json.dumps(measure(args.stop, args.repeats, solvers)))
        return
    builds = args.builds.split(",") if args.builds else []
    rounds = args.rounds if builds else 1
    print(f"seed scenario over {args.stop} s, dt {DT}, CPU time; per event: median and range "
          f"of {args.repeats * rounds} repeats; FMU calls per event beyond the run without "
          "events")
    if not builds:
        print_table("", [measure(args.stop, args.repeats, solvers)], solvers)
        return
    reports: dict[str, list[dict[str, Any]]] = {build_dir: [] for build_dir in builds}
    for _ in range(rounds):
        for build_dir in builds:
            reports[build_dir].append(measure_in(build_dir, args.stop, args.repeats, solvers))
    for build_dir in builds:
        print_table(build_dir, reports[build_dir], solvers)
    if len(builds) > 1:
        for solver in solvers:
            old, new = (statistics.median(per_event(reports[b], solver, "declarative")[0])
                        for b in (builds[0], builds[-1]))
            print(f"pendulum_{solver} declarative per event, {builds[-1]} / {builds[0]}: "
                  f"{new / old:.2f}")


if __name__ == "__main__":
    main()
