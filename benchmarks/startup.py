"""Start-up costs, this checkout's syssimx against a baseline commit's and FMPy, side by side in
one run. Every figure comes from fresh processes, best of REPEATS:

- `import syssimx`, `from syssimx import FMUComponent, System` (what a script needs) and
  `import fmpy` (user + system CPU of the whole interpreter);
- `syssimx simulate` and `fmpy simulate` of one FMU on the same grid, as whole processes (CPU
  and wall);
- 1000 FMUComponents of one FMU built, then initialized in one System (CPU), after a
  two-component system was initialized, so every side has loaded the FMU, the engine and its
  imports once;
- 10 000 connections added to a chain of 10 001 one-input Python components (CPU);
- chains of 1000, 2000 and 4000 gain FMUs connected and initialized (CPU, and per component:
  linear time shows as a flat column).

Children run with bytecode caching on, as an installed package has its bytecode (each side
runs once untimed first). The baseline's python/ and src/ are taken from git (`git archive`),
so both sides use the same engine library. Needs SYSSIMX_BUILD_DIR (or an installed package)
for the engine and the FMUs.

    python benchmarks/startup.py [--baseline main] [--repeats 5]
"""

from __future__ import annotations

import argparse
import io
import json
import os
import resource
import subprocess
import sys
import tarfile
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
COMPONENTS = 1000
CONNECTIONS = 10_000
CHAINS = (1000, 2000, 4000)
SIMULATED_FMU = "pendulum_euler"
STOP_TIME, STEP = "10", "0.01"


# ------------------------------------------------------------------ measured in a child
def _warm_up(path: str) -> None:
    """Two gain FMUs connected and initialized: the FMU, the engine and every import a large
    system needs are loaded before anything is measured."""
    from syssimx import Connection, FMUComponent, System

    warm = System("warm")
    for name in ("a", "b"):
        warm.add_component(FMUComponent(name, path))
    warm.add_connection(Connection("a", "y", "b", "u"))
    warm.initialize(0.0)


def _components() -> dict[str, float]:
    from syssimx import FMUComponent, System, fmus

    path = fmus.path("gain")
    _warm_up(path)
    start = time.process_time()
    made = [FMUComponent(f"g{i}", path) for i in range(COMPONENTS)]
    built = time.process_time()
    system = System("many")
    for component in made:
        system.add_component(component)
    system.initialize(0.0)
    return {"built": built - start, "initialized": time.process_time() - built}


def _connections() -> dict[str, float]:
    from syssimx import Connection, CoSimComponent, PortSpec, PortType, System

    system = System("chain")
    for i in range(CONNECTIONS + 1):
        relay = CoSimComponent(f"r{i}")
        relay.input_specs["u"] = PortSpec("u", PortType.REAL, "in")
        relay.output_specs["y"] = PortSpec("y", PortType.REAL, "out")
        system.add_component(relay)
    start = time.process_time()
    for i in range(CONNECTIONS):
        system.add_connection(Connection(f"r{i}", "y", f"r{i + 1}", "u"))
    return {"added": time.process_time() - start}


def _chains() -> dict[str, float]:
    from syssimx import Connection, FMUComponent, System, fmus

    path = fmus.path("gain")
    _warm_up(path)
    measured = {}
    for length in CHAINS:
        system = System("chain")
        for i in range(length):
            system.add_component(FMUComponent(f"g{i}", path))
        start = time.process_time()
        for i in range(length - 1):
            system.add_connection(Connection(f"g{i}", "y", f"g{i + 1}", "u"))
        system.initialize(0.0)
        measured[str(length)] = time.process_time() - start
    return measured


CHILDREN: dict[str, Callable[[], dict[str, float]]] = {
    "components": _components, "connections": _connections, "chains": _chains}


# ------------------------------------------------------------------ the parent
def _environment(pythonpath: Path | None) -> dict[str, str]:
    environment = dict(os.environ)
    environment.pop("PYTHONDONTWRITEBYTECODE", None)
    if "SYSSIMX_BUILD_DIR" in environment:  # the simulations run in a temporary directory
        environment["SYSSIMX_BUILD_DIR"] = os.path.abspath(environment["SYSSIMX_BUILD_DIR"])
    if pythonpath is not None:
        environment["PYTHONPATH"] = str(pythonpath)
    return environment


def _process(arguments: list[str], pythonpath: Path | None, cwd: Path) -> tuple[float, float]:
    """(user + system CPU seconds, wall seconds) of one child process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([sys.executable, *arguments], env=_environment(pythonpath), cwd=cwd,
                   check=True, capture_output=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), wall


def _child(what: str, pythonpath: Path) -> dict[str, float]:
    output = subprocess.run([sys.executable, __file__, "--child", what],
                            env=_environment(pythonpath), check=True, capture_output=True,
                            text=True).stdout
    return json.loads(output)


def _best(measurements: list[dict[str, float]]) -> dict[str, float]:
    return {key: min(m[key] for m in measurements) for key in measurements[0]}


def _baseline_tree(ref: str, directory: Path) -> Path:
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", ref, "python", "src"],
                             check=True, capture_output=True).stdout
    with tarfile.open(fileobj=io.BytesIO(archive)) as tar:
        tar.extractall(directory, filter="data")
    return directory / "python"


def _simulations(fmu: str, work: Path) -> dict[str, list[str]]:
    return {
        "syssimx simulate": ["-m", "syssimx.cli", "simulate", fmu, "--stop-time", STOP_TIME,
                             "--step-size", STEP, "-o", str(work / "syssimx.csv")],
        "fmpy simulate": ["-m", "fmpy", "simulate", fmu, "--stop-time", STOP_TIME,
                          "--output-interval", STEP, "--output-file", str(work / "fmpy.csv")],
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", default="main", help="git ref of the code to compare with")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--child", choices=tuple(CHILDREN), help=argparse.SUPPRESS)
    options = parser.parse_args()
    if options.child:
        print(json.dumps(CHILDREN[options.child]()))
        return
    from syssimx import fmus

    fmu = str(fmus.path(SIMULATED_FMU))
    with tempfile.TemporaryDirectory() as temporary:
        work = Path(temporary)
        sides = {"this checkout": ROOT / "python",
                 f"baseline {options.baseline}": _baseline_tree(options.baseline, work)}
        imports = {"fmpy": (["-c", "import fmpy"], None)}
        simulations = {"fmpy simulate": (_simulations(fmu, work)["fmpy simulate"], None)}
        for side, path in sides.items():
            imports[f"syssimx, {side}"] = (["-c", "import syssimx"], path)
            imports[f"FMUComponent and System, {side}"] = (
                ["-c", "from syssimx import FMUComponent, System"], path)
            simulations[f"syssimx simulate, {side}"] = (
                _simulations(fmu, work)["syssimx simulate"], path)
        processes = {**imports, **simulations}
        for arguments, path in processes.values():  # compiles the bytecode, fills caches
            _process(arguments, path, work)
        runs: dict[str, list[tuple[float, float]]] = {name: [] for name in processes}
        for _ in range(options.repeats):  # interleaved: a drift of the machine hits all
            for name, (arguments, path) in processes.items():
                runs[name].append(_process(arguments, path, work))
        children = {(side, what): _best([_child(what, path) for _ in range(options.repeats)])
                    for side, path in sides.items() for what in ("components", "connections")}
        chains = {side: _child("chains", path) for side, path in sides.items()}

    print(f"best of {options.repeats}; CPU = user + system seconds")
    print("\nimport (CPU s)")
    for name in imports:
        print(f"  {name:40}{min(cpu for cpu, _ in runs[name]):8.3f}")
    fmpy_import = min(cpu for cpu, _ in runs["fmpy"])
    for side in sides:
        ratio = min(cpu for cpu, _ in runs[f"syssimx, {side}"]) / fmpy_import
        used = min(cpu for cpu, _ in runs[f"FMUComponent and System, {side}"]) / fmpy_import
        print(f"  / import fmpy, {side}: import syssimx {ratio:.2f}, FMUComponent and System "
              f"{used:.2f}")
    print(f"\none FMU ({SIMULATED_FMU}, {STOP_TIME} s, step {STEP}) as a whole process"
          f"\n  {'':40}{'CPU s':>8}{'wall s':>8}")
    for name in simulations:
        print(f"  {name:40}{min(c for c, _ in runs[name]):8.3f}"
              f"{min(w for _, w in runs[name]):8.3f}")
    fmpy_cpu = min(c for c, _ in runs["fmpy simulate"])
    fmpy_wall = min(w for _, w in runs["fmpy simulate"])
    for side in sides:
        own = runs[f"syssimx simulate, {side}"]
        print(f"  syssimx / fmpy, {side}: CPU {min(c for c, _ in own) / fmpy_cpu:.2f}, "
              f"wall {min(w for _, w in own) / fmpy_wall:.2f}")
    print(f"\n{'CPU s':38}{'built':>10}{'initialized':>13}{'together':>10}"
          f"{f'{CONNECTIONS} connections':>19}")
    for side in sides:
        built = children[side, "components"]["built"]
        initialized = children[side, "components"]["initialized"]
        print(f"{f'{side}, {COMPONENTS} components':38}{built:10.3f}{initialized:13.3f}"
              f"{built + initialized:10.3f}{children[side, 'connections']['added']:19.3f}")
    print("\nchain of gain FMUs connected and initialized (CPU s, µs per component)")
    for side in sides:
        cells = "".join(f"{length:>6}: {chains[side][str(length)]:6.3f} s "
                        f"({1e6 * chains[side][str(length)] / length:5.0f} µs)"
                        for length in CHAINS)
        print(f"  {side:28}{cells}")


if __name__ == "__main__":
    main()
