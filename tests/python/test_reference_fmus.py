"""Every FMI 2.0 Co-Simulation Reference FMU (modelica/Reference-FMUs), a user's FMU that no one
on this project wrote, runs through syssimx (an FMUComponent in a System, and the command line)
exactly as through FMPy's simulate_fmu, and reproduces the model's reference result.

Tolerances: against FMPy 1e-9 relative (the same binary stepped on the same grid: any
difference would be ours). Against `<Model>_out.csv` 1e-12 relative: the reference results come
from the Reference FMUs' own simulator running the same model code with its fixed-step solver
on the same grid, written with 17 significant digits (an exact round trip); FMPy reproduces
them to the last bit, so only a different compiler's rounding may remain.

The folder is found through SYSSIMX_REFERENCE_FMUS or at <repository>/../shared/reference-fmus.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.util import read_csv
from reference_root import reference_root
from syssimx import Connection, FMUComponent, JacobiAlgorithm, System, TableSource
from syssimx.cli import main

FOLDER = reference_root() / "fmi2"
if not FOLDER.is_dir():
    pytest.skip(f"the Reference FMUs are absent (no folder {FOLDER}): set SYSSIMX_REFERENCE_FMUS "
                "to the folder holding fmi2/, or place it at <repository>/../shared/"
                "reference-fmus", allow_module_level=True)

MODELS = ["BouncingBall", "Dahlquist", "Feedthrough", "Resource", "Stair", "VanDerPol"]
RTOL_FMPY = 1e-9
RTOL_REFERENCE = 1e-12


def fmu(model: str) -> str:
    return str(FOLDER / f"{model}.fmu")


def outputs(model: str) -> list[str]:
    """The outputs syssimx carries: Real, Integer, Enumeration and Boolean (not String)."""
    return [v.name for v in read_model_description(fmu(model)).modelVariables
            if v.causality == "output" and v.type in ("Real", "Integer", "Enumeration",
                                                      "Boolean")]


def read_result(path: Path) -> dict[str, np.ndarray]:
    """A result CSV (FMPy's format or ours) as columns of numbers; booleans read as 0 and 1,
    text columns are left out."""
    with path.open(newline="") as stream:
        rows = list(csv.reader(stream))
    # ours heads a column "name [unit]" and writes booleans True/False
    header = [name.strip('"').split(" [")[0] for name in rows[0]]
    numbers = {"true": 1.0, "false": 0.0}
    columns = {}
    for j, name in enumerate(header):
        try:
            columns[name] = np.array([numbers[row[j].lower()] if row[j].lower() in numbers
                                      else float(row[j]) for row in rows[1:]])
        except ValueError:
            continue
    return columns


def reference_result(model: str) -> dict[str, np.ndarray]:
    return read_result(FOLDER / f"{model}_out.csv")


def run_system(model: str, t0: float, tf: float, dt: float) -> dict[str, np.ndarray]:
    system = System(model)
    system.add_component(FMUComponent("M", fmu(model)))
    system.initialize(t0)
    t, values = system.run(t0, tf, dt)["M"]
    return {"time": t.copy(), **{name: v.copy() for name, v in values.items()}}


def run_cli(model: str, tmp_path: Path, *options: str) -> dict[str, np.ndarray]:
    path = tmp_path / f"{model}.csv"
    assert main(["simulate", fmu(model), "--output", str(path), *options]) == 0
    return read_result(path)


def assert_same(ours: dict[str, np.ndarray], theirs, names: list[str], rtol: float) -> None:
    assert len(ours["time"]) == len(theirs["time"])
    for name in ["time", *names]:
        np.testing.assert_allclose(np.asarray(ours[name], dtype=float),
                                   np.asarray(theirs[name], dtype=float), rtol=rtol, atol=0,
                                   err_msg=name)


@pytest.mark.parametrize("model", MODELS)
def test_system_equals_fmpy_and_the_reference_result(model: str):
    reference = reference_result(model)
    t = reference["time"]
    t0, tf, dt = float(t[0]), float(t[-1]), float(t[1] - t[0])
    ours = run_system(model, t0, tf, dt)
    theirs = simulate_fmu(fmu(model), start_time=t0, stop_time=tf, output_interval=dt,
                          output=outputs(model))
    assert_same(ours, theirs, outputs(model), RTOL_FMPY)
    assert_same(ours, reference, [n for n in outputs(model) if n in reference], RTOL_REFERENCE)


@pytest.mark.parametrize("model", MODELS)
def test_cli_equals_fmpy_with_the_default_experiment(model: str, tmp_path: Path,
                                                     capsys: pytest.CaptureFixture[str]):
    """No start, stop or step given: both take FMPy's defaults from the default experiment
    (VanDerPol's 0.01 doubles to 0.02 for 1000 steps; Resource has no step: 2e-3 from the
    length). Feedthrough gets its input table: the Int32_input column drives the FMU, the
    other columns name FMI 3.0 variables and are ignored by both."""
    options: list[str] = []
    signals = None
    if model == "Feedthrough":
        options = ["--input", str(FOLDER / "Feedthrough_in.csv")]
        signals = read_csv(FOLDER / "Feedthrough_in.csv")
    ours = run_cli(model, tmp_path, *options)
    theirs = simulate_fmu(fmu(model), input=signals, output=outputs(model))
    assert_same(ours, theirs, outputs(model), RTOL_FMPY)
    # Stair asks to stop at 9 s (fmi2Discard with fmi2Terminated): one line says so, exit 0
    terminated = [line for line in capsys.readouterr().out.splitlines()
                  if " terminated the run at t = " in line]
    end = float(theirs["time"][-1])
    assert [line.split(":")[0] for line in terminated] == (
        [f"Stair terminated the run at t = {end!r}"] if model == "Stair" else [])


def feedthrough_signals() -> np.ndarray:
    """Inputs for each kind of Feedthrough input: a ramp with a jump (a repeated time stamp)
    at 0.5, a discrete real, an integer, a boolean and an enumeration changing at 1.0; the
    table starts after t0 and ends before the stop time (first and last rows hold)."""
    dtype = [("time", np.float64), ("Float64_continuous_input", np.float64),
             ("Float64_discrete_input", np.float64), ("Int32_input", np.int32),
             ("Boolean_input", np.bool_), ("Enumeration_input", np.int32)]
    return np.array([(0.2, 1.0, 3.0, -7, False, 1), (0.5, 2.5, 3.0, -7, False, 1),
                     (0.5, -1.0, 3.0, -7, False, 1), (1.0, 0.0, 4.5, 12, True, 2),
                     (1.55, 5.5, 4.5, 12, True, 2)], dtype=dtype)


FEEDTHROUGH_IO = [("Float64_continuous_input", "Float64_continuous_output"),
                  ("Float64_discrete_input", "Float64_discrete_output"),
                  ("Int32_input", "Int32_output"), ("Boolean_input", "Boolean_output"),
                  ("Enumeration_input", "Enumeration_output")]


def test_feedthrough_follows_an_input_table_as_in_fmpy():
    """A TableSource driving the FMU in a Jacobi System (each step starts from the table at its
    start time, as FMPy sets inputs before doStep) gives FMPy's numbers."""
    signals = feedthrough_signals()
    system = System("feedthrough")
    system.add_component(FMUComponent("F", fmu("Feedthrough")))
    system.add_component(TableSource("u", signals, hold=["Float64_discrete_input"]))
    for port, _ in FEEDTHROUGH_IO:
        system.add_connection(Connection("u", port, "F", port))
    system.set_algorithm(JacobiAlgorithm())
    system.initialize(0.0)
    t, values = system.run(0.0, 2.0, 0.05)["F"]
    theirs = simulate_fmu(fmu("Feedthrough"), stop_time=2.0, output_interval=0.05,
                          input=signals, output=[out for _, out in FEEDTHROUGH_IO])
    assert_same({"time": t, **values}, theirs, [out for _, out in FEEDTHROUGH_IO], RTOL_FMPY)
    # The inputs really move. The output at t is the input set at the step's start t - 0.05:
    # first row held at 0, the ramp at 0.25 and 0.45, the right side of the jump at 0.5.
    assert values["Float64_continuous_output"][[0, 6, 10, 11]].tolist() == [1.0, 1.25, 2.25, -1.0]
    assert values["Int32_output"][[0, 20, 21]].tolist() == [-7, -7, 12]


def test_cli_input_file_drives_the_feedthrough_as_in_fmpy(tmp_path: Path):
    path = tmp_path / "signals.csv"
    signals = feedthrough_signals()
    with path.open("w", newline="") as stream:
        writer = csv.writer(stream)
        writer.writerow(signals.dtype.names)
        writer.writerows([[repr(float(x)) for x in row] for row in signals.tolist()])
    ours = run_cli("Feedthrough", tmp_path, "--input", str(path), "--step-size", "0.05")
    theirs = simulate_fmu(fmu("Feedthrough"), output_interval=0.05, input=read_csv(path),
                          output=[out for _, out in FEEDTHROUGH_IO])
    assert_same(ours, theirs, [out for _, out in FEEDTHROUGH_IO], RTOL_FMPY)
