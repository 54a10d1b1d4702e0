"""One system description, run by SysSimX 0.4.3 and by syssimx side by side: wall time ratio.

`run_from_config(description, tf=..., dt=...)` (build, initialize, run) on both:

  quickstart   examples/quickstart.yaml (SysSimX's LinearSource -> Integrator, two Python
               components), 10 000 steps
  coupled      two pendulum FMUs and the torsion spring FMU in SysSimX's own schema (class
               "syssimx.components:FMUComponent", args fmu_path), 2 000 steps; needs fmpy in
               SysSimX's environment

SysSimX runs in its own virtual environment (--syssimx-python, default: the one
seed_scenario.py creates). Packages that environment lacks (PyYAML, fmpy and what fmpy
imports) are lent from this one through a folder of links on its PYTHONPATH; SysSimX's own
code is never shadowed.

    python benchmarks/yaml_system.py [--repeat N] [--syssimx-python PATH]
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path
from typing import Any

import yaml
from syssimx import fmus
from syssimx.system.loader import run_from_config

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
CASES = {"quickstart": {"tf": 100.0, "dt": 0.01, "probe": ("Integrator", "y")},
         "coupled": {"tf": 20.0, "dt": 0.01, "probe": ("P1", "theta")}}

LENDABLE = ("yaml", "fmpy", "attr", "attrs", "lxml")

CHILD = textwrap.dedent('''
    import importlib.util, json, statistics, sys, time
    from syssimx.system.loader import run_from_config
    yaml_path, json_path, tf, dt, repeat, component, port = sys.argv[1:8]
    path = yaml_path if importlib.util.find_spec("yaml") else json_path
    walls = []
    for _ in range(int(repeat)):
        start = time.perf_counter()
        result = run_from_config(path, tf=float(tf), dt=float(dt))
        walls.append(time.perf_counter() - start)
    t, values = result[component]
    print(json.dumps({"wall": statistics.median(walls), "value": float(values[port][-1]),
                      "samples": len(t), "read": path.rsplit(".", 1)[1]}))
''')


def coupled_description() -> dict[str, Any]:
    """examples/coupled_pendulums.yaml in SysSimX's schema (no syssimx 'fmu' entries)."""
    config = yaml.safe_load((EXAMPLES / "coupled_pendulums.yaml").read_text())
    for entry in config["components"]:
        entry["class"] = "syssimx.components:FMUComponent"
        entry["args"] = {"fmu_path": fmus.path(entry.pop("fmu")), **entry.get("args", {})}
        entry["args"].pop("group", None)
    return config


def descriptions(directory: Path) -> dict[str, tuple[Path, Path]]:
    """Each case as a YAML file and the same mapping as JSON."""
    configs = {"quickstart": yaml.safe_load((EXAMPLES / "quickstart.yaml").read_text()),
               "coupled": coupled_description()}
    files = {}
    for name, config in configs.items():
        yaml_path, json_path = directory / f"{name}.yaml", directory / f"{name}.json"
        yaml_path.write_text(yaml.safe_dump(config))
        json_path.write_text(json.dumps(config))
        files[name] = (yaml_path, json_path)
    return files


def measure_ours(path: Path, case: dict[str, Any], repeat: int) -> dict[str, Any]:
    walls = []
    for _ in range(repeat):
        start = time.perf_counter()
        result = run_from_config(path, tf=case["tf"], dt=case["dt"],
                                 allowed_modules=["quickstart"])  # its classes beside it
        walls.append(time.perf_counter() - start)
    component, port = case["probe"]
    t, values = result[component]
    return {"wall": statistics.median(walls), "value": float(values[port][-1]),
            "samples": len(t), "read": "yaml"}


def lend_packages(python: str, directory: Path) -> list[str]:
    """Link the LENDABLE packages `python` cannot import into `directory`; their names."""
    probe = subprocess.run(
        [python, "-c", "import importlib.util, sys; print(' '.join(n for n in sys.argv[1:] "
         "if importlib.util.find_spec(n) is None))", *LENDABLE],
        capture_output=True, text=True, check=True,
        env={k: v for k, v in os.environ.items() if k != "PYTHONPATH"})
    lent = []
    for name in probe.stdout.split():
        spec = importlib.util.find_spec(name)
        if spec is None or spec.origin is None:
            continue
        origin = Path(spec.origin)
        source = origin.parent if origin.name == "__init__.py" else origin
        (directory / source.name).symlink_to(source)
        lent.append(name)
    return lent


def measure_syssimx(python: str, files: tuple[Path, Path], case: dict[str, Any],
                    repeat: int, lent: Path) -> dict[str, Any]:
    # SysSimX from its environment, not this source tree; the quickstart classes from examples/
    environment = {**{k: v for k, v in os.environ.items() if k != "PYTHONPATH"},
                   "PYTHONPATH": os.pathsep.join([str(EXAMPLES), str(lent)])}
    with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as script:
        script.write(CHILD)
    try:
        run = subprocess.run(
            [python, script.name, str(files[0]), str(files[1]), str(case["tf"]),
             str(case["dt"]), str(repeat), *case["probe"]],
            capture_output=True, text=True, env=environment)
    finally:
        Path(script.name).unlink()
    if run.returncode != 0:
        last = (run.stderr.strip().splitlines() or ["no output"])[-1]
        return {"error": last}
    return json.loads(run.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per case (median taken)")
    parser.add_argument("--syssimx-python", help="python of an environment with SysSimX 0.4.3")
    args = parser.parse_args()
    python = args.syssimx_python
    if python is None:
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from seed_scenario import syssimx_environment

        python = str(syssimx_environment())
    sys.path.insert(0, str(EXAMPLES))  # the quickstart classes for our run too

    with tempfile.TemporaryDirectory() as directory:
        files = descriptions(Path(directory))
        lent = Path(directory) / "lent"
        lent.mkdir()
        names = lend_packages(python, lent)
        if names:
            print(f"lent to SysSimX's environment from this one: {', '.join(names)}")
        print(f"{'case':<12}{'steps':>7}{'syssimx ms':>12}{'SysSimX ms':>12}{'ratio':>8}"
              f"{'last value (both)':>22}  SysSimX read")
        for name, case in CASES.items():
            ours = measure_ours(files[name][0], case, args.repeat)
            theirs = measure_syssimx(python, files[name], case, args.repeat, lent)
            steps = round(case["tf"] / case["dt"])
            if "error" in theirs:
                print(f"{name:<12}{steps:>7}{ours['wall'] * 1e3:>12.2f}  SysSimX failed: "
                      f"{theirs['error']}")
                continue
            same = "equal" if abs(ours["value"] - theirs["value"]) <= 1e-9 * max(
                1.0, abs(ours["value"])) else f"{ours['value']:.6g} / {theirs['value']:.6g}"
            print(f"{name:<12}{steps:>7}{ours['wall'] * 1e3:>12.2f}"
                  f"{theirs['wall'] * 1e3:>12.1f}{theirs['wall'] / ours['wall']:>8.1f}"
                  f"{same:>22}  {theirs['read']}")


if __name__ == "__main__":
    main()
