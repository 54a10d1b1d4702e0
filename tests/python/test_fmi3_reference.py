"""Every FMI 3.0 Co-Simulation Reference FMU (modelica/Reference-FMUs built for FMI 3.0) runs
through syssimx (an FMUComponent in a System, and the command line) exactly as through FMPy's
simulate_fmu, and reproduces the model's reference result; the clocked one is refused by name.

syssimx instantiates them with event mode and early return (they declare hasEventMode and
canReturnEarlyAfterIntermediateUpdate), FMPy by default without: the FMU then handles its
events inside doStep. Both step the same fixed-step Euler on the same grid, so the numbers agree
to the last bit; the bound is FMPy's usual 1e-9 relative.

Against `<Model>_out.csv` (the FMI 2.0 collection's): 1e-12 relative. The FMI 3.0 build runs
the same model code with the same fixed internal step as the FMI 2.0 build that wrote the
reference, and the FMI 3.0 event handling (early return, event mode) lands on that same step,
so only a different compiler's rounding could remain (none is seen). Roberts is compared with
FMPy only: the collection's Roberts_out.csv holds BouncingBall's columns (h, v), not Roberts'.

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
from syssimx.errors import FMUFileError

ROOT = reference_root()
FOLDER = ROOT / "fmi3"
if not FOLDER.is_dir():
    pytest.skip(f"the FMI 3.0 Reference FMUs are absent (no folder {FOLDER}): set "
                "SYSSIMX_REFERENCE_FMUS to the folder holding fmi3/ and fmi2/, or place it at "
                "<repository>/../shared/reference-fmus", allow_module_level=True)

MODELS = ["BouncingBall", "Dahlquist", "Feedthrough", "Roberts", "Stair", "VanDerPol"]
# Roberts' default experiment runs to 1e8 s on a 1e-3 internal step: both stop at 3 s instead
GRIDS = {"Roberts": (0.0, 3.0, 0.01)}
RTOL_FMPY = 1e-9
RTOL_REFERENCE = 1e-12
EXCHANGED = ("Float64", "Float32", "Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32",
             "Int64", "UInt64", "Boolean", "Enumeration")


def fmu(model: str) -> str:
    return str(FOLDER / f"{model}.fmu")


def outputs(model: str) -> list[str]:
    """The outputs syssimx carries as ports (String and Binary ones are values, not ports)."""
    return [v.name for v in read_model_description(fmu(model)).modelVariables
            if v.causality == "output" and v.type in EXCHANGED]


def read_result(path: Path) -> dict[str, np.ndarray]:
    """A result CSV (FMPy's or ours) as columns of numbers; booleans as 0 and 1, text left out."""
    with path.open(newline="") as stream:
        rows = list(csv.reader(stream))
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


def grid(model: str) -> tuple[float, float, float]:
    if model in GRIDS:
        return GRIDS[model]
    t = read_result(ROOT / "fmi2" / f"{model}_out.csv")["time"]
    return float(t[0]), float(t[-1]), float(t[1] - t[0])


def assert_same(ours: dict[str, np.ndarray], theirs, names: list[str], rtol: float) -> None:
    assert len(ours["time"]) == len(theirs["time"])
    for name in ["time", *names]:
        np.testing.assert_allclose(np.asarray(ours[name], dtype=float),
                                   np.asarray(theirs[name], dtype=float), rtol=rtol, atol=0,
                                   err_msg=name)


def test_the_co_simulation_models_are_all_but_the_clocked_one():
    found = {path.stem for path in FOLDER.glob("*.fmu")
             if read_model_description(str(path)).coSimulation is not None}
    assert found == set(MODELS)
    assert {path.stem for path in FOLDER.glob("*.fmu")} - found == {"Clocks"}


@pytest.mark.parametrize("model", MODELS)
def test_system_equals_fmpy_and_the_reference_result(model: str):
    t0, tf, dt = grid(model)
    system = System(model)
    system.add_component(FMUComponent("M", fmu(model)))
    system.initialize(t0)
    t, values = system.run(t0, tf, dt)["M"]
    ours = {"time": t, **values}
    theirs = simulate_fmu(fmu(model), start_time=t0, stop_time=tf, output_interval=dt,
                          output=outputs(model))
    assert_same(ours, theirs, outputs(model), RTOL_FMPY)
    if model != "Roberts":
        reference = read_result(ROOT / "fmi2" / f"{model}_out.csv")
        assert_same(ours, reference, [n for n in outputs(model) if n in reference],
                    RTOL_REFERENCE)


@pytest.mark.parametrize("model", [m for m in MODELS if m != "Feedthrough"])
def test_cli_equals_fmpy_with_the_default_experiment(model: str, tmp_path: Path,
                                                     capsys: pytest.CaptureFixture[str]):
    """No grid given: both take FMPy's defaults from the default experiment (Roberts' stop
    time is given to both). Stair asks to stop at 9 s: one line says so, exit 0."""
    options = ["--stop-time", "3"] if model == "Roberts" else []
    path = tmp_path / f"{model}.csv"
    assert main(["simulate", fmu(model), "--output", str(path), *options]) == 0
    theirs = simulate_fmu(fmu(model), output=outputs(model),
                          **({"stop_time": 3.0} if model == "Roberts" else {}))
    assert_same(read_result(path), theirs, outputs(model), RTOL_FMPY)
    terminated = [line.split(":")[0] for line in capsys.readouterr().out.splitlines()
                  if " terminated the run at t = " in line]
    end = float(theirs["time"][-1])
    assert terminated == ([f"Stair terminated the run at t = {end!r}"] if model == "Stair"
                          else [])


@pytest.mark.filterwarnings("ignore:invalid value encountered in cast:RuntimeWarning")  # FMPy's
def test_feedthrough_refuses_the_collections_input_file_at_its_64_bit_extremes(
        capsys: pytest.CaptureFixture[str]):
    """Feedthrough_in.csv drives each integer input to its type's extremes. Every column but
    Int64_input and UInt64_input fits (UInt32 4294967295 too: UInt32, Int64 and UInt64 travel
    as Real ports, exact up to 2**53); Int64_input's -2**63 at t = 0 is refused naming the
    variable instead of being rounded. (FMPy does not pass them exactly either: its input table
    is float64, and Int64_output reads -2**63 where the file says 2**63 - 1.)"""
    signals = ROOT / "fmi2" / "Feedthrough_in.csv"
    assert main(["simulate", fmu("Feedthrough"), "--input", str(signals)]) == 1
    assert capsys.readouterr().err.splitlines()[-1] == (
        "syssimx: error: component 'Feedthrough': fmi3SetFloat64 refused at t=0: variable "
        "'Int64_input' "
        "(Int64) cannot take -9.2233720368547758e+18: outside "
        "-9007199254740992..9007199254740992 (its range, within the 2^53 up to which the "
        "engine's Real ports carry integers exactly)")
    theirs = simulate_fmu(fmu("Feedthrough"), input=read_csv(signals),
                          output=["Int64_output"])
    assert theirs["Int64_output"][-1] == -2**63


def test_feedthrough_follows_every_column_within_2_53_as_in_fmpy(tmp_path: Path):
    """Feedthrough_in.csv with its two 64-bit columns brought within 2**53 (Int64 from -2**53
    to 2**53, UInt64 from 0 to 2**53; the other seven columns as in the file, each at its
    type's extremes, UInt32 4294967295 among them): every output column equals FMPy's
    exactly."""
    table = read_csv(ROOT / "fmi2" / "Feedthrough_in.csv")
    columns = ["Int8_input", "UInt8_input", "Int16_input", "UInt16_input", "Int32_input",
               "UInt32_input"]
    wide = {"Int64_input": (-(2**53), 2**53), "UInt64_input": (0, 2**53)}
    path = tmp_path / "within_2_53.csv"
    with path.open("w", newline="") as stream:
        writer = csv.writer(stream)
        writer.writerow(["time", *columns, *wide])
        writer.writerows([[repr(float(row["time"])), *(int(row[n]) for n in columns),
                           *(values[i] for values in wide.values())]
                          for i, row in enumerate(table)])
    out = tmp_path / "out.csv"
    assert main(["simulate", fmu("Feedthrough"), "--input", str(path), "--output",
                 str(out)]) == 0
    names = [n.replace("input", "output") for n in [*columns, *wide]]
    theirs = simulate_fmu(fmu("Feedthrough"), input=read_csv(path), output=names)
    ours = read_result(out)
    assert_same(ours, theirs, names, 0.0)
    assert ours["UInt32_output"][-1] == 2**32 - 1
    assert ours["Int64_output"][0] == -(2**53) and ours["UInt64_output"][-1] == 2**53


def test_feedthrough_in_a_system_carries_every_type_as_fmpy():
    """A TableSource drives the Float32, Float64, integer, Boolean and Enumeration inputs of
    the FMI 3.0 Feedthrough; the outputs are FMPy's to the bit (Float32 rounds 0.1 the same)."""
    pairs = [("Float32_continuous_input", np.float64, [0.1, 0.1, -2.5]),
             ("Float64_continuous_input", np.float64, [0.1, 0.1, -2.5]),
             ("Int8_input", np.int32, [-128, -128, 127]),
             ("UInt16_input", np.int32, [0, 0, 65535]),
             ("Int64_input", np.int32, [-(2**31), -(2**31), 2**31 - 1]),
             ("UInt64_input", np.int32, [0, 0, 7]),
             ("Boolean_input", np.bool_, [False, False, True]),
             ("Enumeration_input", np.int32, [1, 1, 2])]
    signals = np.array(list(zip([0.0, 0.95, 1.0], *(values for _, _, values in pairs),
                                strict=True)),
                       dtype=[("time", np.float64), *((n, d) for n, d, _ in pairs)])
    system = System("feedthrough")
    system.add_component(FMUComponent("F", fmu("Feedthrough")))
    system.add_component(TableSource("u", signals, hold=["Float32_continuous_input",
                                                         "Float64_continuous_input"]))
    for name, _, _ in pairs:
        system.add_connection(Connection("u", name, "F", name))
    system.set_algorithm(JacobiAlgorithm())
    system.initialize(0.0)
    t, values = system.run(0.0, 2.0, 0.1)["F"]
    names = [n.replace("input", "output") for n, _, _ in pairs]
    theirs = simulate_fmu(fmu("Feedthrough"), stop_time=2.0, output_interval=0.1,
                          input=signals, output=names)
    assert_same({"time": t, **values}, theirs, names, RTOL_FMPY)
    assert values["Float32_continuous_output"][1] == float(np.float32(0.1)) != 0.1
    assert values["Int64_output"][-1] == 2**31 - 1 and values["Enumeration_output"][-1] == 2


def test_clocks_is_refused_as_a_co_simulation_component():
    with pytest.raises(FMUFileError) as info:
        FMUComponent("C", fmu("Clocks"))
    assert "FMI 3.0 Scheduled Execution is not supported as a Co-Simulation" in str(info.value)
