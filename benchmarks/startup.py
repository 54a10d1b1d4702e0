"""Start-up costs, this checkout's syssimx against a baseline commit's, side by side in one run.

Measured in fresh processes (best of REPEATS, CPU time):
- `import syssimx` against `import fmpy` (user + system CPU of the whole interpreter);
- 1000 FMUComponents of one FMU (gain), after one component was made, so both sides have
  loaded the FMU and the engine once;
- 10 000 connections added to a chain of 10 001 one-input Python components.

The baseline's python/ and src/ are taken from git (`git archive`), so both sides use the same
engine library. Needs SYSSIMX_BUILD_DIR (or an installed package) for the engine and the FMU.

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
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
COMPONENTS = 1000
CONNECTIONS = 10_000


def _components() -> float:
    from syssimx import FMUComponent, fmus

    path = fmus.path("gain")
    FMUComponent("first", path)
    start = time.process_time()
    made = [FMUComponent(f"g{i}", path) for i in range(COMPONENTS)]
    elapsed = time.process_time() - start
    del made
    return elapsed


def _connections() -> float:
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
    return time.process_time() - start


def _child_cpu(arguments: list[str], pythonpath: Path | None) -> float:
    """User + system CPU seconds of one child process."""
    environment = dict(os.environ)
    if pythonpath is not None:
        environment["PYTHONPATH"] = str(pythonpath)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, *arguments], env=environment, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def _measured(what: str, pythonpath: Path) -> float:
    environment = dict(os.environ, PYTHONPATH=str(pythonpath))
    output = subprocess.run([sys.executable, __file__, "--child", what], env=environment,
                            check=True, capture_output=True, text=True).stdout
    return float(json.loads(output)[what])


def _baseline_tree(ref: str, directory: Path) -> Path:
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", ref, "python", "src"],
                             check=True, capture_output=True).stdout
    with tarfile.open(fileobj=io.BytesIO(archive)) as tar:
        tar.extractall(directory, filter="data")
    return directory / "python"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", default="main", help="git ref of the code to compare with")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--child", choices=("components", "connections"), help=argparse.SUPPRESS)
    options = parser.parse_args()
    if options.child:
        print(json.dumps({options.child: {"components": _components,
                                          "connections": _connections}[options.child]()}))
        return
    with tempfile.TemporaryDirectory() as temporary:
        sides = {"this checkout": ROOT / "python",
                 f"baseline {options.baseline}": _baseline_tree(options.baseline,
                                                                Path(temporary))}
        best = {(side, what): min(measure() for _ in range(options.repeats))
                for side, path in sides.items()
                for what, measure in (
                    ("import", lambda path=path: _child_cpu(["-c", "import syssimx"], path)),
                    ("components", lambda path=path: _measured("components", path)),
                    ("connections", lambda path=path: _measured("connections", path)))}
        fmpy_import = min(_child_cpu(["-c", "import fmpy"], None)
                          for _ in range(options.repeats))
    print(f"best of {options.repeats}, CPU seconds")
    print(f"{'':38}{'import syssimx':>16}{f'{COMPONENTS} components':>18}"
          f"{f'{CONNECTIONS} connections':>19}")
    for side in sides:
        print(f"{side:38}{best[side, 'import']:16.3f}{best[side, 'components']:18.3f}"
              f"{best[side, 'connections']:19.3f}")
    current, baseline = sides
    for what in ("import", "components", "connections"):
        ratio = best[baseline, what] / best[current, what]
        print(f"{what}: baseline / this checkout = {ratio:.1f}x")
    print(f"import fmpy: {fmpy_import:.3f} s; import syssimx / import fmpy = "
          f"{best[current, 'import'] / fmpy_import:.2f} (baseline "
          f"{best[baseline, 'import'] / fmpy_import:.2f})")


if __name__ == "__main__":
    main()
