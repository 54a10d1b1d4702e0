"""The seed scenario exported as one FMU (examples/pendulum_wall.yaml: the CVODE pendulum
against a wall, the engine's restart handler), run by the tools users bring, side by side with
syssimx's own run of the description:

1. FMPy's simulate_fmu of the FMI 2.0 and the FMI 3.0 export (output interval 0.05 s), in the
   Python given (a virtual environment with FMPy only; default: this one, with syssimx made
   unimportable);
2. libcosim (libcosimpy, in a Python of its own) running the FMI 2.0 export inside an OSP
   system structure (fixed step 0.05 s, 20 steps).

Printed: the largest deviation from syssimx's own run at the grid points, the wall hit inside
(the export's last_event_time output) and the values at t = 0.5 s and 1 s that
tests/python/test_export_fmu.py asserts for libcosim.

    python -m venv cosim && cosim/bin/pip install libcosimpy==0.0.6
    python -m venv fmpy-only && fmpy-only/bin/pip install fmpy
    python benchmarks/exported_fmu_peers.py --libcosimpy-python cosim/bin/python \\
        --fmpy-python fmpy-only/bin/python
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "python"))
from exported_fmus import (
    OUTPUTS,
    STEP,
    STOP_TIME,
    export_seed,
    osp_structure,
    run_with_fmpy_alone,
    seed_system,
)

# run by the libcosimpy interpreter: the structure file, the variables, the steps, the JSON file
LIBCOSIM_RUN = """
import json, sys
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimObserver import CosimObserver
path, names, steps, target = sys.argv[1], json.loads(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
execution = CosimExecution.from_osp_config_file(path)
observer = CosimObserver.create_last_value()
execution.add_observer(observer)
index = execution.slave_index_from_instance_name("wall")
references = {v.name.decode(): v.reference for v in execution.slave_variables(index)}
rows = []
for _ in range(steps):
    execution.step(1)
    rows.append([observer.last_integer_values(index, [references[n]])[0] if n == "events"
                 else observer.last_real_values(index, [references[n]])[0] for n in names])
with open(target, "w") as out:
    json.dump(rows, out)
"""


def own_run() -> tuple[np.ndarray, dict[str, np.ndarray], float]:
    system = seed_system()
    system.initialize(0.0)
    result = system.run(0.0, STOP_TIME, STEP)
    times, values = system.components["P"].get_history_arrays(["theta", "omega"])
    last = np.append(times[1:] != times[:-1], True)  # an event instant's sample after it
    return times[last], {f"P.{n}": v[last] for n, v in values.items()}, result.events[0].t


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--fmpy-python", default=sys.executable,
                        help="a Python with FMPy (default: this one)")
    parser.add_argument("--libcosimpy-python", default=None,
                        help="a Python with libcosimpy installed (default: libcosim skipped)")
    args = parser.parse_args()
    times, values, event_time = own_run()
    grid = np.isclose(times / STEP, np.round(times / STEP), rtol=0, atol=1e-9)
    print(f"syssimx's own run: wall hit at {event_time!r} s")
    with tempfile.TemporaryDirectory() as folder:
        exported = {v: export_seed(Path(folder), v) for v in ("2.0", "3.0")}
        for version, fmu in exported.items():
            result = run_with_fmpy_alone(fmu, python=args.fmpy_python)
            deviation = max(float(np.max(np.abs(np.asarray(result[n]) - values[n][grid])))
                            for n in values)
            hit = int(np.searchsorted(result["time"], event_time))
            print(f"FMPy, FMI {version} export: max |deviation| {deviation:.3g}, "
                  f"last_event_time {result['last_event_time'][hit]!r}, "
                  f"events {result['events'][-1]}")
        if args.libcosimpy_python:
            structure = osp_structure(Path(folder), exported["2.0"])
            target = Path(folder) / "libcosim.json"
            steps = round(STOP_TIME / STEP)
            subprocess.run([args.libcosimpy_python, "-c", LIBCOSIM_RUN, str(structure),
                            json.dumps(OUTPUTS), str(steps), str(target)], check=True,
                           capture_output=True)
            rows = np.array(json.loads(target.read_text()))
            own = np.column_stack([values[n][grid][1:] for n in OUTPUTS[:2]])
            deviation = float(np.max(np.abs(rows[:, :2] - own)))
            print(f"libcosim, FMI 2.0 export in an OSP file: max |deviation| {deviation:.3g}")
            for k in (round(0.5 / STEP) - 1, steps - 1):
                print(f"   t = {(k + 1) * STEP:.2f}: " + ", ".join(
                    f"{n} = {v!r}" for n, v in zip(OUTPUTS, rows[k], strict=True)))


if __name__ == "__main__":
    main()
