"""One SSP run by syssimx and by libcosim (libcosimpy), side by side: the largest deviation.

The coupled pendulums (two pendulum FMUs and the torsion spring, the torque into P2 through a
LinearTransformation) are exported with System.to_ssp, with a fixed step as the Open
Simulation Platform annotation. syssimx reads the archive back and runs it with its Jacobi
coupling (libcosim's fixed-step algorithm); libcosim reads the same file in a Python of its
own, because libcosimpy is installed apart:

    python -m venv /tmp/cosim && /tmp/cosim/bin/pip install libcosimpy
    python benchmarks/ssp_vs_libcosim.py --libcosimpy-python /tmp/cosim/bin/python
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
import coupled_pendulums as coupled_pendulums_example
from syssimx import JacobiAlgorithm, System
from syssimx.ssp import read

STOP, STEP = 2.0, 0.01
SIGNALS = (("P1", "theta"), ("P2", "theta"), ("Spring", "tau2"))

# run by the libcosimpy interpreter: the folder of the unpacked SSP, the signals, the number of
# steps, the JSON file to write (libcosim logs on stdout)
LIBCOSIM_RUN = """
import json, sys
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimObserver import CosimObserver
execution = CosimExecution.from_ssp_file(sys.argv[1])
observer = CosimObserver.create_last_value()
execution.add_observer(observer)
signals = json.loads(sys.argv[2])
where = []
for component, variable in signals:
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


def coupled_pendulums() -> System:
    """examples/coupled_pendulums, the spring's torque into P2 as 0.5 * tau2 + 0.1, Jacobi."""
    return coupled_pendulums_example.build(JacobiAlgorithm(), torque2_factor=0.5,
                                           torque2_offset=0.1)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--libcosimpy-python", default=os.environ.get("LIBCOSIMPY_PYTHON"),
                        required="LIBCOSIMPY_PYTHON" not in os.environ,
                        help="a Python interpreter with libcosimpy installed")
    args = parser.parse_args()
    steps = round(STOP / STEP)
    with tempfile.TemporaryDirectory() as folder:
        archive = coupled_pendulums().to_ssp(Path(folder) / "pendulums.ssp", 0.0, STOP, STEP)
        imported = read(archive)
        imported.system.set_algorithm(JacobiAlgorithm())
        imported.system.initialize(0.0)
        result = imported.system.run(0.0, STOP, STEP)
        ours = np.array([result[c][1][v][1:] for c, v in SIGNALS]).T
        unpacked = Path(folder) / "unpacked"
        with zipfile.ZipFile(archive) as opened:
            opened.extractall(unpacked)
        rows = Path(folder) / "libcosim.json"
        subprocess.run([args.libcosimpy_python, "-c", LIBCOSIM_RUN, str(unpacked),
                        json.dumps(SIGNALS), str(steps), str(rows)], capture_output=True,
                       check=True)
        theirs = np.array(json.loads(rows.read_text()))
    print(f"{steps} steps of {STEP} s, Jacobi (syssimx) vs fixed-step (libcosim), one SSP file")
    for column, (component, variable) in enumerate(SIGNALS):
        deviation = np.abs(ours[:, column] - theirs[:, column]).max()
        print(f"  {component}.{variable:<6} largest deviation {deviation:.3e} "
              f"(range {np.ptp(ours[:, column]):.3g})")
    print(f"largest deviation overall: {np.abs(ours - theirs).max():.3e}")


if __name__ == "__main__":
    main()
