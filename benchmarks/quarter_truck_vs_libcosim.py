"""libcosim's quarter truck (an OSP system structure whose two FMI 2.0 FMUs are set a String
parameter, solverType = "Euler") read by syssimx and by libcosim (libcosimpy), at a fixed step.

The file runs libcosim's ECCO algorithm. For numbers that do not depend on how each tool
picks its steps, both read a copy with <Algorithm>fixedStep and no <EccoConfiguration>:
libcosim then steps its fixed-step algorithm at the file's BaseStepSize (1e-4 s), syssimx the
Jacobi algorithm at the same step. Printed: the largest deviation of each output over
STOP_TIME, and libcosim's values at every SAMPLE_EVERY-th step, the constants
tests/python/test_string_variables.py holds.

libcosimpy is installed apart, in a Python of its own:

    python -m venv /tmp/cosim && /tmp/cosim/bin/pip install libcosimpy==0.0.6
    python benchmarks/quarter_truck_vs_libcosim.py --libcosimpy-python /tmp/cosim/bin/python \\
        --truck ../shared/coupling-samples/quarter_truck
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import tempfile
import warnings
from pathlib import Path

import numpy as np
from syssimx import JacobiAlgorithm
from syssimx.osp import read as read_osp

STEP = 1e-4  # the file's BaseStepSize
STOP_TIME = 0.1
SAMPLE_EVERY = 100  # steps between the printed constants
SIGNALS = [("chassis", "position"), ("chassis", "velocity"), ("wheel", "position"),
           ("wheel", "velocity"), ("wheel", "out_spring_damper_f")]

# run by the libcosimpy interpreter: the OSP file, the signals, the number of steps, the JSON
# file to write (a row of the signals after each step; libcosim logs on stdout)
LIBCOSIM_RUN = """
import json, sys
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimObserver import CosimObserver
execution = CosimExecution.from_osp_config_file(sys.argv[1])
observer = CosimObserver.create_last_value()
execution.add_observer(observer)
where = []
for component, variable in json.loads(sys.argv[2]):
    index = execution.slave_index_from_instance_name(component)
    references = {v.name.decode(): v.reference for v in execution.slave_variables(index)}
    where.append((index, references[variable]))
rows = []
for _ in range(int(sys.argv[3])):
    execution.step(1)
    rows.append([observer.last_real_values(i, [r])[0] for i, r in where])
with open(sys.argv[4], "w") as out:
    json.dump(rows, out)
"""


def fixed_step_copy(truck: Path, folder: Path) -> Path:
    """The quarter truck's folder copied, its OSP file set to libcosim's fixed step."""
    shutil.copytree(truck, folder)
    path = folder / "OspSystemStructure.xml"
    text = path.read_text()
    text = text.replace("<Algorithm>ecco</Algorithm>", "<Algorithm>fixedStep</Algorithm>")
    text = re.sub(r"\s*<EccoConfiguration>.*?</EccoConfiguration>", "", text, flags=re.DOTALL)
    path.write_text(text)
    return path


def steps() -> int:
    return round(STOP_TIME / STEP)


def libcosim(python: str, path: Path, folder: Path) -> np.ndarray:
    rows = folder / "libcosim.json"
    subprocess.run([python, "-c", LIBCOSIM_RUN, str(path), json.dumps(SIGNALS), str(steps()),
                    str(rows)], capture_output=True, check=True)
    return np.array(json.loads(rows.read_text()))


def syssimx(path: Path) -> np.ndarray:
    system = read_osp(path).system
    system.set_algorithm(JacobiAlgorithm())
    system.initialize(0.0)
    result = system.run(0.0, STOP_TIME, STEP)
    return np.array([result[c][1][v][1:] for c, v in SIGNALS]).T


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--libcosimpy-python", default=os.environ.get("LIBCOSIMPY_PYTHON"),
                        required="LIBCOSIMPY_PYTHON" not in os.environ,
                        help="a Python interpreter with libcosimpy installed")
    parser.add_argument("--truck", type=Path, required=True,
                        help="the quarter_truck folder (OspSystemStructure.xml and its FMUs)")
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        path = fixed_step_copy(args.truck.resolve(), folder / "truck")
        ours, theirs = syssimx(path), libcosim(args.libcosimpy_python, path, folder)
    print(f"quarter truck, {steps()} steps of {STEP} s, Jacobi vs libcosim's fixed step:")
    for column, (component, variable) in enumerate(SIGNALS):
        deviation = np.abs(ours[:, column] - theirs[:, column]).max()
        print(f"  {f'{component}.{variable}':<27} largest deviation {deviation:.3e} "
              f"(range {np.ptp(theirs[:, column]):.3g})")
    print(f"libcosim's values after every {SAMPLE_EVERY}th step (rows), {SIGNALS} (columns):")
    for row in theirs[SAMPLE_EVERY - 1::SAMPLE_EVERY]:
        print("    (" + ", ".join(repr(float(value)) for value in row) + "),")


if __name__ == "__main__":
    main()
