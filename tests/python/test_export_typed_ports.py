"""Integer and Boolean ports and parameters of members in an exported FMU: FMI 2.0 Integer and
Boolean, FMI 3.0 Int32 and Boolean variables, run by FMPy in a Python that cannot import syssimx
as syssimx runs the system; a String port is refused, a call of the wrong type names the
variable."""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np
import pytest
from exported_fmus import run_with_fmpy_alone
from fmpy.validation import validate_fmu
from reference_root import reference_root
from syssimx import FMUComponent, System, fmus
from syssimx.errors import ConfigurationError

STAIR_STOP = 10.0
STAIR_STEP = 0.5
CONTACT_STOP = 1.0
CONTACT_STEP = 0.05


def reference_fmu(fmi_version: str, name: str) -> str:
    path = reference_root() / f"fmi{fmi_version[0]}" / f"{name}.fmu"
    if not path.is_file():
        pytest.skip(f"the Reference FMUs are absent (no {path}): set SYSSIMX_REFERENCE_FMUS")
    return str(path)


def alone(name: str, fmu: str) -> System:
    system = System(f"{name}_alone")
    system.add_component(FMUComponent(name, fmu))
    return system


def declared(fmu: Path, name: str) -> str:
    """The type the modelDescription declares the variable `name` of (FMPy's reading)."""
    from fmpy import read_model_description

    return {v.name: v.type for v in read_model_description(fmu).modelVariables}[name]


@pytest.mark.parametrize("fmi_version", ["2.0", "3.0"])
def test_stair_exported_alone_counts_under_fmpy_as_under_syssimx(tmp_path, fmi_version):
    """The Reference Stair, whose one output is an Integer counter stepping each second: by
    default its export offers the counter, FMPy's run gives syssimx's own at every grid point,
    and the modelDescription passes FMPy's validation."""
    stair = reference_fmu(fmi_version, "Stair")
    fmu = tmp_path / f"stair_{fmi_version[0]}.fmu"
    alone("S", stair).export_fmu(fmu, fmi_version=fmi_version, step_size=STAIR_STEP)
    assert validate_fmu(str(fmu)) == []
    assert declared(fmu, "S.counter") == ("Integer" if fmi_version == "2.0" else "Int32")
    result = run_with_fmpy_alone(fmu, ["S.counter"], stop_time=STAIR_STOP, interval=STAIR_STEP)
    system = alone("S", stair)
    system.initialize(0.0)
    system.run(0.0, STAIR_STOP, STAIR_STEP)
    times, values = system.components["S"].get_history_arrays(["counter"])
    np.testing.assert_array_equal(result["time"], times)
    np.testing.assert_array_equal(result["S.counter"], values["counter"])
    assert sorted(set(result["S.counter"])) == list(range(1, 11))  # it counts


def contact(sense: int) -> System:
    """The Euler pendulum against a wall at 0, released at -0.3 rad: the Integer parameter
    sense says on which side the wall is."""
    system = System("contact")
    pendulum = FMUComponent("P", fmus.path("pendulum_contact_euler"))
    pendulum.set_parameters(theta0=-0.3, sense=sense)
    system.add_component(pendulum)
    return system


@pytest.mark.parametrize("fmi_version", ["2.0", "3.0"])
def test_an_integer_parameter_set_by_fmpy_reaches_the_member(tmp_path, fmi_version):
    """sense, exported as an Integer (Int32) parameter with its start -1, set to +1 by FMPy:
    the run, a Real and a Boolean output, is syssimx's with sense +1 (the pendulum bounces off
    the wall), not the one with the start."""
    fmu = tmp_path / f"contact_{fmi_version[0]}.fmu"
    contact(-1).export_fmu(fmu, fmi_version=fmi_version, outputs=["P.theta", "P.contact"],
                           parameters=["P.sense"], step_size=CONTACT_STEP)
    assert validate_fmu(str(fmu)) == []
    result = run_with_fmpy_alone(fmu, ["P.theta", "P.contact"], {"P.sense": 1},
                                 stop_time=CONTACT_STOP, interval=CONTACT_STEP)
    runs = {}
    for sense in (1, -1):
        system = contact(sense)
        system.initialize(0.0)
        system.run(0.0, CONTACT_STOP, CONTACT_STEP)
        runs[sense] = system.components["P"].get_history_arrays(["theta", "contact"])
    times, values = runs[1]
    np.testing.assert_array_equal(result["time"], times)
    np.testing.assert_array_equal(result["P.theta"], values["theta"])
    np.testing.assert_array_equal(np.asarray(result["P.contact"], dtype=float),
                                  values["contact"])
    assert not np.array_equal(runs[-1][1]["theta"], values["theta"])


@pytest.mark.parametrize("fmi_version", ["2.0", "3.0"])
def test_inputs_set_by_fmpy_before_initialization_pass_through_from_the_start(tmp_path,
                                                                            fmi_version):
    """The Reference Feedthrough's Boolean, Int32 and Float64 inputs exported (starts false, 0
    and 0), set by FMPy to true, -7 and 2.5 before initialization: its outputs give them back
    at every point, the start time too (the member is initialized with them)."""
    fmu = tmp_path / f"feedthrough_{fmi_version[0]}.fmu"
    alone("F", reference_fmu(fmi_version, "Feedthrough")).export_fmu(
        fmu, fmi_version=fmi_version,
        inputs=["F.Boolean_input", "F.Int32_input", "F.Float64_continuous_input"],
        outputs=["F.Boolean_output", "F.Int32_output", "F.Float64_continuous_output"],
        step_size=0.1)
    assert validate_fmu(str(fmu)) == []
    assert declared(fmu, "F.Boolean_input") == "Boolean"
    result = run_with_fmpy_alone(
        fmu, ["F.Boolean_output", "F.Int32_output", "F.Float64_continuous_output"],
        {"F.Boolean_input": True, "F.Int32_input": -7, "F.Float64_continuous_input": 2.5},
        stop_time=0.5, interval=0.1)
    assert len(result["time"]) == 6
    assert all(value is True for value in result["F.Boolean_output"])
    assert result["F.Int32_output"] == [-7] * 6
    assert result["F.Float64_continuous_output"] == [2.5] * 6


def test_a_string_port_is_refused_naming_it(tmp_path):
    """The engine holds values as numbers: a String output requested is refused by name, and
    the default selection leaves it out."""
    system = alone("F", reference_fmu("2.0", "Feedthrough"))
    with pytest.raises(ConfigurationError, match=r"'F\.String_output'.*STRING"):
        system.export_fmu(tmp_path / "strings.fmu", outputs=["F.String_output"])
    fmu = system.export_fmu(tmp_path / "defaults.fmu")
    text = zipfile.ZipFile(fmu).read("modelDescription.xml").decode()
    assert "F.Int32_output" in text and "String" not in text


def test_a_call_of_the_wrong_type_is_an_error_naming_the_variable(tmp_path, capsys):
    """fmi2GetReal of the Integer counter fails, its message naming it (FMPy's default logger
    prints each message); fmi2GetInteger of it gives the count, fmi2SetInteger of it (an
    output) fails naming it too."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    fmu = tmp_path / "stair.fmu"
    alone("S", reference_fmu("2.0", "Stair")).export_fmu(fmu, step_size=STAIR_STEP)
    description = read_model_description(fmu)
    counter = {v.name: v.valueReference for v in description.modelVariables}["S.counter"]
    stair = FMU2Slave(guid=description.guid, instanceName="stair",
                      unzipDirectory=extract(fmu, unzipdir=tmp_path / "unzipped"),
                      modelIdentifier=description.coSimulation.modelIdentifier)
    stair.instantiate()
    stair.setupExperiment(startTime=0.0)
    stair.enterInitializationMode()
    stair.exitInitializationMode()
    for k in range(4):
        stair.doStep(k * STAIR_STEP, STAIR_STEP)
    assert stair.getInteger([counter]) == [3]
    with pytest.raises(Exception, match="fmi2GetReal failed"):
        stair.getReal([counter])
    assert f"the variable 'S.counter' (value reference {counter}) is an Integer, not a Real" \
        in capsys.readouterr().out
    with pytest.raises(Exception, match="fmi2SetInteger failed"):
        stair.setInteger([counter], [5])
    assert "'S.counter' is an output" in capsys.readouterr().out
    stair.terminate()
    stair.freeInstance()


def test_a_member_with_a_name_of_5000_letters_exports_and_runs(tmp_path):
    """Names travel in the export map for the binary's messages, cut to fit its line bound:
    a member named by 5000 Greek letters (10000 bytes) still runs under FMPy."""
    name = "λ" * 5000
    fmu = tmp_path / "long.fmu"
    alone(name, reference_fmu("2.0", "Stair")).export_fmu(fmu, step_size=STAIR_STEP)
    result = run_with_fmpy_alone(fmu, [f"{name}.counter"], stop_time=2.0, interval=STAIR_STEP)
    assert result[f"{name}.counter"] == [1, 1, 2, 2, 3]
