"""libcosim's ECCO algorithm and syssimx's error-controlled steps on one power-bonded OSP
system (tests/python/ecco_structure.py: a pendulum FMU and the torsion spring-damper FMU joined
by a torque/angular velocity bond), against the monolithic solution (solve_ivp, rtol 1e-12).

For each tolerance (the <EccoConfiguration>'s RelativeTolerance = AbsoluteTolerance):
libcosim runs the file (CosimExecution.from_osp_config_file, one macro step at a time until
the stop time) in its own interpreter; syssimx reads the same file (syssimx.osp.read: Jacobi,
held inputs, steps chosen without rollback by the bond's energy residual under ECCO's PI
controller, with the file's settings), then runs the same system with second-order inputs, with
its own coupling error measure (input order 0, 1, 2, with rollback), and on a fixed step of
exactly libcosim's number of macro steps. Printed: macro steps, the end error and the largest error
(libcosim's at each of its steps, syssimx's at the 0.05 s output grid and the end).

With --truck (the folder of libcosim's quarter truck: its OSP file as shipped, Chassis.fmu and
Wheel.fmu, which cannot interpolate, declare no output dependencies, and whose wheel force
depends directly on its velocity input) the same comparison on libcosim's own ECCO system over
TRUCK_STOP_TIME: libcosim's ECCO, syssimx's ECCO as read (the undeclared dependencies make a
loop, solved), and syssimx coupling it explicitly as libcosim does with extrapolated held inputs
and the coupling-error control. Printed: macro steps, doSteps per FMU, and the largest chassis
velocity error on a 0.01 s grid against a Richardson reference 2 b - a from syssimx's Jacobi
runs at fixed steps a = 1e-6 and b = 5e-7 s.

libcosimpy is installed apart, in a Python of its own:

    python -m venv /tmp/cosim && /tmp/cosim/bin/pip install libcosimpy
    python benchmarks/ecco_vs_libcosim.py --libcosimpy-python /tmp/cosim/bin/python \\
        --truck ../shared/coupling-samples/quarter_truck
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "python"))
from ecco_structure import STOP_TIME, Ecco, monolithic, write_structure
from syssimx import GaussSeidelAlgorithm, JacobiAlgorithm, StepControl
from syssimx.osp import read as read_osp

TOLERANCES = (1e-3, 1e-4, 1e-5)
OUTPUT_STEP = 0.05  # syssimx's output grid: the file's MaximumStepSize, so it bounds no step

# run by the libcosimpy interpreter: the structure's folder, the stop time, the JSON file to
# write [[t, theta], ...] after each macro step (libcosim logs on stdout)
LIBCOSIM_RUN = """
import json, sys
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimObserver import CosimObserver
path, stop, out = sys.argv[1], float(sys.argv[2]), sys.argv[3]
execution = CosimExecution.from_osp_config_file(path)
observer = CosimObserver.create_last_value()
execution.add_observer(observer)
index = execution.slave_index_from_instance_name("Pendulum")
theta = {v.name.decode(): v.reference for v in execution.slave_variables(index)}["theta"]
rows = []
while not rows or rows[-1][0] < stop - 1e-9:
    execution.step(1)
    rows.append([execution.status().current_time * 1e-9,
                 observer.last_real_values(index, [theta])[0]])
with open(out, "w") as f:
    json.dump(rows, f)
"""


@dataclass(frozen=True)
class Row:
    way: str
    steps: int
    end_error: float
    max_error: float


def libcosim(python: str, structure: Path) -> Row:
    out = structure.parent / "libcosim.json"
    subprocess.run([python, "-c", LIBCOSIM_RUN, str(structure.parent), str(STOP_TIME),
                    str(out)], capture_output=True, check=True)
    rows = np.array(json.loads(out.read_text()))
    error = np.abs(rows[:, 1] - monolithic(rows[:, 0]))
    return Row("libcosim ECCO (energy residual, PI)", len(rows), float(error[-1]),
               float(error.max()))


def syssimx(structure: Path, way: str, algorithm: JacobiAlgorithm | None = None,
            step: float = OUTPUT_STEP) -> Row:
    system = read_osp(structure).system
    if algorithm is not None:
        system.set_algorithm(algorithm)
    system.initialize(0.0)
    result = system.run(0.0, STOP_TIME, step)
    t, pendulum = result["Pendulum"]
    error = np.abs(pendulum["theta"] - monolithic(t))
    return Row(way, result.statistics.macro_steps, float(error[-1]), float(error.max()))


def rows_for(python: str, folder: Path, tolerance: float) -> list[Row]:
    ecco = Ecco(tolerance)
    structure = write_structure(folder, ecco)
    theirs = libcosim(python, structure)

    def control(rollback: bool) -> StepControl:
        return StepControl(rtol=tolerance, atol=tolerance, min_step=ecco.min_step,
                           max_step=ecco.max_step, initial_step=ecco.step_size,
                           safety=ecco.safety, rollback=rollback)

    as_read = read_osp(structure).system.algorithm
    fixed = STOP_TIME / theirs.steps
    rows = [theirs, syssimx(structure, "syssimx <Algorithm>ecco as read (energy, order 0)")]
    rows.append(syssimx(structure, "syssimx ECCO's energy residual, order 2",
                        JacobiAlgorithm(input_order=2, step_control=as_read.step_control)))
    for order in (0, 1, 2):
        rows.append(syssimx(structure, f"syssimx coupling error, non-iterative, order {order}",
                            JacobiAlgorithm(input_order=order, step_control=control(False))))
    rows.append(syssimx(structure, "syssimx coupling error, non-iterative, order 2, G.-S.",
                        GaussSeidelAlgorithm(input_order=2, step_control=control(False))))
    rows.append(syssimx(structure, "syssimx coupling error, rollback, order 2",
                        JacobiAlgorithm(input_order=2, step_control=control(True))))
    for order in (0, 2):
        rows.append(syssimx(structure, f"syssimx fixed, libcosim's step count, order {order}",
                            JacobiAlgorithm(input_order=order), fixed))
    return rows


TRUCK_STOP_TIME = 0.1
TRUCK_GRID = np.linspace(0.0, TRUCK_STOP_TIME, 11)
TRUCK_FMUS = 2


@dataclass(frozen=True)
class TruckRow:
    way: str
    steps: int
    do_steps: int  # per FMU, rejected steps included
    max_error: float

# run by the libcosimpy interpreter: the OSP file, the stop time, the JSON file to write
# [[t, chassis velocity], ...] after each macro step
LIBCOSIM_TRUCK_RUN = """
import json, sys
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimObserver import CosimObserver
path, stop, out = sys.argv[1], float(sys.argv[2]), sys.argv[3]
execution = CosimExecution.from_osp_config_file(path)
observer = CosimObserver.create_last_value()
execution.add_observer(observer)
index = execution.slave_index_from_instance_name("chassis")
velocity = {v.name.decode(): v.reference for v in execution.slave_variables(index)}["velocity"]
rows = [[0.0, observer.last_real_values(index, [velocity])[0]]]
while rows[-1][0] < stop - 1e-9:
    execution.step(1)
    rows.append([execution.status().current_time * 1e-9,
                 observer.last_real_values(index, [velocity])[0]])
with open(out, "w") as f:
    json.dump(rows, f)
"""


def truck_velocity(path: Path, algorithm: JacobiAlgorithm | None, undeclared: str,
                   step: float) -> tuple[np.ndarray, int, int]:
    """The chassis velocity on TRUCK_GRID, the macro steps and the doSteps per FMU."""
    system = read_osp(path).system
    system.undeclared_dependencies = undeclared
    if algorithm is not None:
        system.set_algorithm(algorithm)
    system.initialize(0.0)
    result = system.run(0.0, TRUCK_STOP_TIME, step)
    times, chassis = result["chassis"]
    statistics = result.statistics
    return (np.interp(TRUCK_GRID, times, chassis["velocity"]), statistics.macro_steps,
            statistics.do_step_calls // TRUCK_FMUS)


def truck_rows(python: str, path: Path, folder: Path) -> list[TruckRow]:
    fine = [truck_velocity(path, JacobiAlgorithm(), "all", step)[0] for step in (1e-6, 5e-7)]
    reference = 2 * fine[1] - fine[0]
    out = folder / "libcosim_truck.json"
    subprocess.run([python, "-c", LIBCOSIM_TRUCK_RUN, str(path), str(TRUCK_STOP_TIME),
                    str(out)], capture_output=True, check=True)
    theirs = np.array(json.loads(out.read_text()))
    steps = len(theirs) - 1
    error = float(np.abs(np.interp(TRUCK_GRID, theirs[:, 0], theirs[:, 1]) - reference).max())
    rows = [TruckRow("libcosim ECCO (energy residual, PI)", steps, steps, error)]

    def control(tolerance: float, rollback: bool = True) -> StepControl:
        return StepControl(rtol=tolerance, atol=tolerance, min_step=1e-6, max_step=0.01,
                           rollback=rollback)

    ways: list[tuple[str, JacobiAlgorithm | None, str, float]] = [
        ("syssimx <Algorithm>ecco as read (a loop, solved)", None, "all", 0.01),
        ("syssimx fixed, libcosim's step count, held", JacobiAlgorithm(), "none",
         TRUCK_STOP_TIME / steps)]
    for tolerance in (1e-6, 1e-7):
        for order in (1, 2):
            way = f"syssimx explicit, G.-S., order {order} extrapolated, tol {tolerance:g}"
            ways.append((way, GaussSeidelAlgorithm(
                input_order=order, extrapolate_held_inputs=True,
                step_control=control(tolerance)), "none", 0.01))
    ways.append(("syssimx explicit, G.-S., order 2 extrapolated, tol 1e-07, no rollback",
                 GaussSeidelAlgorithm(input_order=2, extrapolate_held_inputs=True,
                                      step_control=control(1e-7, rollback=False)),
                 "none", 0.01))
    for way, algorithm, undeclared, step in ways:
        velocity, macro_steps, do_steps = truck_velocity(path, algorithm, undeclared, step)
        rows.append(TruckRow(way, macro_steps, do_steps,
                             float(np.abs(velocity - reference).max())))
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--libcosimpy-python", default=os.environ.get("LIBCOSIMPY_PYTHON"),
                        required="LIBCOSIMPY_PYTHON" not in os.environ,
                        help="a Python interpreter with libcosimpy installed")
    parser.add_argument("--truck", type=Path,
                        help="libcosim's quarter_truck folder (OspSystemStructure.xml, FMUs)")
    args = parser.parse_args()
    warnings.simplefilter("ignore")  # the reader's note on ECCO's PI settings
    print(f"pendulum + spring-damper, power bond, {STOP_TIME} s; |theta error| [rad]")
    print(f"{'tolerance':>9}  {'way':<56}{'steps':>8}{'end error':>12}{'max error':>12}")
    with tempfile.TemporaryDirectory() as name:
        for tolerance in TOLERANCES:
            for row in rows_for(args.libcosimpy_python, Path(name) / f"{tolerance:g}",
                                tolerance):
                print(f"{tolerance:>9g}  {row.way:<56}{row.steps:>8}{row.end_error:>12.3g}"
                      f"{row.max_error:>12.3g}")

    if args.truck is None:
        return
    print(f"\nlibcosim's quarter truck as shipped, {TRUCK_STOP_TIME} s; |chassis velocity error|"
          " [m/s]")
    print(f"{'way':<66}{'steps':>8}{'doSteps':>9}{'max error':>12}")
    with tempfile.TemporaryDirectory() as name:
        for row in truck_rows(args.libcosimpy_python,
                              args.truck.resolve() / "OspSystemStructure.xml", Path(name)):
            print(f"{row.way:<66}{row.steps:>8}{row.do_steps:>9}{row.max_error:>12.3g}")


if __name__ == "__main__":
    main()
