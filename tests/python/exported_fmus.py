"""The seed scenario (examples/pendulum_wall.yaml: the CVODE pendulum against a wall, the
engine's restart handler) exported as FMUs, and run by FMPy in a Python that cannot import
syssimx, from a copy of the FMU in a fresh folder: what the export tests share."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

from syssimx.system.loader import build_system

SEED = Path(__file__).resolve().parents[2] / "examples" / "pendulum_wall.yaml"
STOP_TIME = 1.0
STEP = 0.05  # the description's run dt, FMPy's output interval
OUTPUTS = ["P.theta", "P.omega", "events", "last_event_time"]

# FMPy alone: syssimx is made unimportable first, the FMU is a copy in a folder of its own
FMPY_RUN = """
import json, sys
sys.modules["syssimx"] = None
import numpy as np
from fmpy import simulate_fmu
path, stop, interval, outputs, starts, inputs, target = sys.argv[1:8]
held = json.loads(inputs)  # constant inputs, FMPy's structured input array
signals = None
if held:
    signals = np.array([(0.0, *held.values()), (float(stop), *held.values())],
                       dtype=[("time", float)] + [(name, float) for name in held])
result = simulate_fmu(path, stop_time=float(stop), output_interval=float(interval),
                      output=json.loads(outputs), start_values=json.loads(starts),
                      input=signals)
with open(target, "w") as out:
    json.dump({name: result[name].tolist() for name in result.dtype.names}, out)
"""

def seed_system() -> Any:
    return build_system(SEED)


def export_seed(folder: Path, fmi_version: str) -> Path:
    """The seed as `folder`/pendulum_wall_<2|3>.fmu, its inner step the description's dt."""
    path = folder / f"pendulum_wall_{fmi_version[0]}.fmu"
    seed_system().export_fmu(path, fmi_version=fmi_version, step_size=STEP, start_time=0.0,
                             stop_time=STOP_TIME)
    return path


def run_with_fmpy_alone(fmu: Path, outputs: list[str] = OUTPUTS,
                        start_values: dict[str, float] | None = None,
                        inputs: dict[str, float] | None = None,
                        stop_time: float = STOP_TIME, interval: float = STEP,
                        python: str = sys.executable) -> dict[str, list[float]]:
    """FMPy's simulate_fmu of a copy of `fmu` in a fresh folder, in `python` with its syssimx
    import made to fail, with `start_values` and constant `inputs`, its output interval
    `interval`: the result's columns by name."""
    with tempfile.TemporaryDirectory() as fresh:
        copy = Path(fresh) / fmu.name
        shutil.copyfile(fmu, copy)
        target = Path(fresh) / "result.json"
        ran = subprocess.run([python, "-c", FMPY_RUN, str(copy), str(stop_time),
                              repr(interval), json.dumps(outputs), json.dumps(start_values or {}),
                              json.dumps(inputs or {}), str(target)], cwd=fresh,
                             capture_output=True, text=True)
        assert ran.returncode == 0, ran.stderr
        return json.loads(target.read_text())


def osp_structure(folder: Path, fmu: Path) -> Path:
    """An OSP system structure in `folder` whose one simulator, "wall", is `fmu`, stepped at
    STEP from 0 (libcosim's fixed-step algorithm)."""
    path = folder / "OspSystemStructure.xml"
    path.write_text(f"""<?xml version="1.0" encoding="utf-8"?>
<OspSystemStructure xmlns="http://opensimulationplatform.com/MSMI/OSPSystemStructure"
                    version="0.1">
  <StartTime>0.0</StartTime>
  <BaseStepSize>{STEP!r}</BaseStepSize>
  <Algorithm>fixedStep</Algorithm>
  <Simulators>
    <Simulator name="wall" source="{fmu.resolve().as_uri()}"/>
  </Simulators>
</OspSystemStructure>
""")
    return path
