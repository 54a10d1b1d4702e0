"""The fixed cost of a run: short members on a reused System against FMPy's reuse loop, and
what `System.run` costs in Python as the component count grows.

1. Members of 20 steps (dt 0.05, theta0 changed per member) of one pendulum FMU, in one process:
   - syssimx, reused System: set_parameters, initialize, run, read the arrays (the plan is
     compiled once; each initialize resets the FMU instance: fmi2Reset, starts, init mode);
   - syssimx, rebuilt: the same with `system.reset()` before each initialize (a fresh plan and a
     fresh instance per member: what every initialize did before plans were reused);
   - syssimx, run_members: the same members in one System.run_members call (each member one
     engine call on the System initialized once, its samples copied);
   - FMPy's reuse loop: one FMU2Slave, `reset` between members, setupExperiment, start value,
     initialization mode, 20 doStep + getReal of the outputs into a list.
   - with `--ecos-python PY`: Ecos (ecospy) in its own virtual environment (PY its Python; the
     tbb library pip installs there is put on the child's library path), in a child process
     (benchmarks/ecos_members.py) that takes its turn in every round: reset, set_real(theta0),
     init, step(20) per member ("ecospy"), and the same stepping one step at a time with the
     outputs read after each ("ecospy, recorded": the samples the other paths keep).
   - with `--baseline REF`: the reused System of the syssimx of git ref REF (its python/
     from `git archive`, the same engine library), in a child process that takes its turn
     in every round.
   Median CPU microseconds per member of `--repeats` rounds of `--members` members (CPU time,
   not wall time: on a shared machine the wall counts the other processes' turns too), and
   ratios to FMPy (and to the baseline, and to ecospy). The load average is printed before
   and after.
2. `System.run` of one step on a chain-free system of N `gain` FMUs (N = 100, 1000, 10000):
   the wall of `System.run` against `ssx_run` called directly on the same engine system for
   the same step; the difference is the Python cost per call, printed per call and per
   component; and the Python function calls one `System.run` makes (counted by a profile
   hook: a figure the machine's load does not move).

    python benchmarks/run_cost.py [--members 200] [--repeats 5] [--components 100,1000,10000]
                                  [--baseline main] [--ecos-python ECOS_VENV/bin/python]
"""

from __future__ import annotations

import argparse
import functools
import io
import json
import os
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from syssimx import FMUComponent, System, fmus
from syssimx.engine import lib

DT, STEPS = 0.05, 20
ROOT = Path(__file__).resolve().parent.parent

# One round of members: (CPU seconds it took, each member's theta after 1 s)
Round = Callable[[np.ndarray], tuple[float, list[float]]]


def syssimx_members(fmu: str, rebuild: bool) -> Callable[[np.ndarray], list[np.ndarray]]:
    pendulum = FMUComponent("P", fmus.path(fmu))
    system = System("member")
    system.add_component(pendulum)

    def run(thetas: np.ndarray) -> list[np.ndarray]:
        out = []
        for theta in thetas:
            if rebuild:
                system.reset()
            pendulum.set_parameters(theta0=float(theta))
            system.initialize(0.0)
            result = system.run(0.0, STEPS * DT, DT)
            out.append(result["P"][1]["theta"])
        return out
    return run


def syssimx_run_members(fmu: str) -> Callable[[np.ndarray], list[np.ndarray]]:
    system = System("member")
    system.add_component(FMUComponent("P", fmus.path(fmu)))

    def run(thetas: np.ndarray) -> list[np.ndarray]:
        runs = system.run_members({"P.theta0": thetas}, 0.0, STEPS * DT, DT)
        return list(runs.last("P.theta")[:, np.newaxis])  # what the rounds read: theta(1 s)
    return run


def fmpy_members(fmu: str) -> Callable[[np.ndarray], list[np.ndarray]]:
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    path = fmus.path(fmu)
    description = read_model_description(path)
    unzipdir = extract(path)
    refs = {v.name: v.valueReference for v in description.modelVariables}
    slave = FMU2Slave(guid=description.guid, unzipDirectory=unzipdir,
                      modelIdentifier=description.coSimulation.modelIdentifier,
                      instanceName="P")
    slave.instantiate()
    theta0, outputs = [refs["theta0"]], [refs["theta"], refs["omega"]]

    def run(thetas: np.ndarray) -> list[np.ndarray]:
        out = []
        for theta in thetas:
            slave.reset()
            slave.setupExperiment(startTime=0.0)
            slave.enterInitializationMode()
            slave.setReal(theta0, [float(theta)])
            slave.exitInitializationMode()
            rows = [slave.getReal(outputs)]
            t = 0.0
            for k in range(1, STEPS + 1):
                slave.doStep(t, DT)
                t = k * DT
                rows.append(slave.getReal(outputs))
            out.append(np.array(rows)[:, 0])
        return out
    return run


def timed(run: Callable[[np.ndarray], list[np.ndarray]]) -> Round:
    """`run` as a Round: its CPU time (the members' angles are read after the clock stops)."""
    def round_of(thetas: np.ndarray) -> tuple[float, list[float]]:
        start = time.process_time()
        series = run(thetas)
        return time.process_time() - start, [float(s[-1]) for s in series]
    return round_of


class ChildMembers:
    """Members run by a child process (`command`), one round per request: the thetas go as
    JSON, the CPU time the child measured and its final angles come back."""

    def __init__(self, command: list[str], environment: dict[str, str]) -> None:
        self.child = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                      text=True, env=environment)

    def __call__(self, thetas: np.ndarray) -> tuple[float, list[float]]:
        assert self.child.stdin is not None and self.child.stdout is not None
        self.child.stdin.write(json.dumps(thetas.tolist()) + "\n")
        self.child.stdin.flush()
        line = self.child.stdout.readline()
        if not line:
            raise RuntimeError(f"the child {self.child.args[0]} ended (status "
                               f"{self.child.wait()})")
        cpu, finals = json.loads(line)
        return cpu, finals

    def close(self) -> None:
        assert self.child.stdin is not None
        self.child.stdin.close()
        self.child.wait()


def baseline_members(fmu: str, pythonpath: Path) -> ChildMembers:
    """The reused-System members of another syssimx (python/ at `pythonpath`)."""
    environment = dict(os.environ, PYTHONPATH=str(pythonpath))
    if "SYSSIMX_BUILD_DIR" in environment:
        environment["SYSSIMX_BUILD_DIR"] = os.path.abspath(environment["SYSSIMX_BUILD_DIR"])
    return ChildMembers([sys.executable, __file__, "--serve", fmu], environment)


def ecos_members(fmu: str, python: str, mode: str) -> ChildMembers:
    """The members run by ecospy in the virtual environment of `python`, whose tbb shared
    library (pip's tbb package, under the environment's lib/) goes on the library path."""
    libraries = {str(found.parent) for found in (Path(python).parent.parent / "lib")
                 .rglob("libtbb.so*")}
    environment = dict(os.environ, LD_LIBRARY_PATH=os.pathsep.join(
        [*sorted(libraries), os.environ.get("LD_LIBRARY_PATH", "")]))
    environment.pop("PYTHONPATH", None)
    script = str(Path(__file__).resolve().parent / "ecos_members.py")
    return ChildMembers([python, script, fmus.path(fmu), mode], environment)


def serve(fmu: str) -> None:
    """The child of BaselineMembers: a round of members per line of thetas read."""
    run = timed(syssimx_members(fmu, rebuild=False))
    for line in sys.stdin:
        print(json.dumps(run(np.array(json.loads(line)))), flush=True)


def baseline_tree(ref: str, directory: Path) -> Path:
    """python/ of git ref `ref`, unpacked under `directory`."""
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", ref, "python"], check=True,
                             capture_output=True).stdout
    with tarfile.open(fileobj=io.BytesIO(archive)) as tar:
        tar.extractall(directory, filter="data")
    return directory / "python"


def member_costs(members: int, repeats: int, baseline: tuple[str, Path] | None,
                 ecos_python: str | None) -> None:
    thetas = np.linspace(0.2, 0.6, members)
    print(f"1. members of {STEPS} steps (dt {DT}), {members} members per round, median of "
          f"{repeats} rounds, in turns")
    before = f"syssimx {baseline[0]}, reused" if baseline is not None else ""
    print(f"{'FMU':<16} {'path':<30} {'CPU us/member':>14} {'/ FMPy':>8}"
          + (f" {'/ ecospy':>9}" if ecos_python is not None else "")
          + (f" {'/ ' + baseline[0]:>10}" if baseline is not None else ""))
    for fmu in ("pendulum_euler", "pendulum_cvode"):
        paths: dict[str, Round] = {
            "syssimx, run_members": timed(syssimx_run_members(fmu)),
            "syssimx, reused System": timed(syssimx_members(fmu, rebuild=False)),
            "syssimx, rebuilt": timed(syssimx_members(fmu, rebuild=True)),
            "FMPy reuse loop": timed(fmpy_members(fmu))}
        children: list[ChildMembers] = []
        if ecos_python is not None:
            for name, mode in (("ecospy", "final"), ("ecospy, recorded", "recorded")):
                children.append(ecos_members(fmu, ecos_python, mode))
                paths[name] = children[-1]
        if baseline is not None:
            children.append(baseline_members(fmu, baseline[1]))
            paths[before] = children[-1]
        times: dict[str, list[float]] = {name: [] for name in paths}
        finals: dict[str, list[float]] = {}
        for name, run in paths.items():  # warm-up, and the final angles compared
            finals[name] = run(thetas[:5])[1]
        for _ in range(repeats):
            for name, run in paths.items():
                times[name].append(run(thetas)[0] / members * 1e6)
        for child in children:
            child.close()
        fmpy = statistics.median(times["FMPy reuse loop"])
        ecos = statistics.median(times["ecospy"]) if ecos_python is not None else None
        earlier = statistics.median(times[before]) if baseline is not None else None
        for name, samples in times.items():
            cost = statistics.median(samples)
            print(f"{fmu:<16} {name:<30} {cost:14.1f} {cost / fmpy:8.2f}"
                  + (f" {cost / ecos:9.2f}" if ecos is not None else "")
                  + (f" {cost / earlier:10.2f}" if earlier is not None else ""))
        reference = np.array(finals["FMPy reuse loop"])
        for name, values in finals.items():
            print(f"{'':<16} {name:<30} max |theta(1 s) - FMPy's| = "
                  f"{np.max(np.abs(np.array(values) - reference)):.1e}")


def python_calls_of(call: Callable[[], object]) -> int:
    """The Python functions `call` runs (C functions not counted)."""
    counted = 0

    def count(_frame: object, event: str, _argument: object) -> None:
        nonlocal counted
        counted += event == "call"

    sys.setprofile(count)
    try:
        call()
    finally:
        sys.setprofile(None)
    return counted


def run_call_cost(counts: list[int], repeats: int) -> None:
    print(f"\n2. System.run of one step (dt 1e-3) on N uncoupled gain FMUs, median of {repeats}")
    print(f"{'N':>6} {'System.run us':>14} {'ssx_run us':>11} {'Python us':>10} "
          f"{'Python us/component':>20} {'Python calls':>13}")
    for count in counts:
        system = System("gains")
        for i in range(count):
            system.add_component(FMUComponent(f"G{i}", fmus.path("gain")))
        system.initialize(0.0)
        plan = system._plan
        assert plan is not None
        t, python_calls, engine_calls = 0.0, [], []
        for _ in range(repeats):
            start = time.perf_counter()
            system.run(t, t + 1e-3, 1e-3)
            python_calls.append(time.perf_counter() - start)
            t = system.t
            start = time.perf_counter()
            lib().ssx_run(plan.sys, t, t + 1e-3, 1e-3)
            engine_calls.append(time.perf_counter() - start)
            t += 1e-3
            system.t = t
        whole, engine = statistics.median(python_calls), statistics.median(engine_calls)
        calls = python_calls_of(functools.partial(system.run, system.t, system.t + 1e-3, 1e-3))
        print(f"{count:6d} {whole * 1e6:14.1f} {engine * 1e6:11.1f} "
              f"{(whole - engine) * 1e6:10.1f} {(whole - engine) / count * 1e6:20.3f} "
              f"{calls:13d}")
        for component in system.components.values():
            component.free()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--members", type=int, default=200)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--components", default="100,1000,10000",
                        help="component counts of part 2, comma-separated (none: skip it)")
    parser.add_argument("--baseline", help="git ref of a syssimx to compare the reused "
                        "System with (its python/, this engine library)")
    parser.add_argument("--ecos-python", help="the Python of a virtual environment with "
                        "ecospy and tbb installed: ecospy's members take their turn too")
    parser.add_argument("--serve", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.serve:
        serve(args.serve)
        return
    print(f"load average {os.getloadavg()[0]:.2f} at the start")
    with tempfile.TemporaryDirectory() as temporary:
        baseline = (args.baseline, baseline_tree(args.baseline, Path(temporary))) \
            if args.baseline else None
        member_costs(args.members, args.repeats, baseline, args.ecos_python)
    if args.components != "none":
        run_call_cost([int(n) for n in args.components.split(",")], args.repeats)
    print(f"load average {os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
