"""Users' system files, as OMSimulator and libcosim wrote them (never edited): `syssimx run`
runs each or refuses it in one line with a reason a user can act on, and the files OMSimulator
tests give OMSimulator's printed numbers."""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import Any

import pytest
from ssp_samples import available_samples
from syssimx import System
from syssimx.cli import main
from syssimx.ssp import Experiment, read

NO_STOP_TIME = "give --stop-time: the file has no stop time"

# every SSD, SSP and OSP system structure among the samples, and what `syssimx run` does: None
# when it runs, else the reason it gives
OUTCOMES = {
    "libcosim/msmi/OspSystemStructure.xml": NO_STOP_TIME,
    "libcosim/msmi/OspSystemStructure_Bond.xml": NO_STOP_TIME,
    "libcosim/msmi/OspSystemStructure_Dahlquist.xml": NO_STOP_TIME,
    "libcosim/msmi/OspSystemStructure_Dahlquist_proxyfmu.xml": NO_STOP_TIME,
    "libcosim/msmi/OspSystemStructure_EndTime.xml": None,
    "libcosim/msmi/OspSystemStructure_proxyfmu.xml": NO_STOP_TIME,
    "libcosim/msmi/msmi2.xml": "not an OSP system structure: its root element is <MSMI>",
    "libcosim/ssp/linear_transformation/SystemStructure.ssd": NO_STOP_TIME,
    "omsimulator/LinearTransformation/SystemStructure.ssd": None,
    "omsimulator/importParameterMappingInline/SystemStructure.ssd": None,
    "omsimulator/import_export_parameters1/SystemStructure.ssd": None,
    "omsimulator/toplevelparameter1/SystemStructure.ssd": None,
}
def system_files(root: Path) -> list[str]:
    """The system files among the samples: SSDs, SSPs and the XML files that are not FMU or
    OSP model descriptions, schemas or OMSimulator's signal filters."""
    found = [p for p in root.rglob("*") if p.suffix in (".ssd", ".ssp")
             or (p.suffix == ".xml" and "schema" not in p.parts
                 and not p.name.endswith("_OspModelDescription.xml")
                 and p.name not in ("modelDescription.xml", "signalFilter.xml"))]
    return sorted(p.relative_to(root).as_posix() for p in found)


def test_the_samples_are_the_files_listed() -> None:
    assert system_files(available_samples()) == sorted(OUTCOMES)


@pytest.mark.parametrize("name", sorted(OUTCOMES))
def test_run_runs_or_refuses_in_one_line(name: str, capsys: pytest.CaptureFixture[str]) -> None:
    """What is left out is one warning line each; a refusal is one error line, the last."""
    path = available_samples() / name
    code = main(["run", str(path), "--quiet"])
    out, err = capsys.readouterr()
    lines = err.splitlines()
    assert all(line.startswith("syssimx: warning: ") for line in lines[:-1])
    reason = OUTCOMES[name]
    if reason is None:
        assert code == 0, err
        assert out.startswith("Completed ")
        assert not any(line.startswith("syssimx: error") for line in lines)
        return
    assert code == 1
    assert lines[-1].startswith(f"syssimx: error: {path}")
    assert reason in lines[-1]


def imported(name: str) -> tuple[System, Experiment]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = read(available_samples() / "omsimulator" / name / "SystemStructure.ssd")
    system = result.system
    system.initialize(0.0)
    system.run(0.0, result.experiment.stop_time, result.experiment.step_size or 0.01)
    return system, result.experiment


def value(system: System, component: str, variable: str) -> Any:
    return system.components[component].get_state()[variable]["value"]


def test_linear_transformation_gives_omsimulators_numbers() -> None:
    """OMSimulator's LinearTransformation1.py prints Gain1.y = 0.0 and Add1.u1 = 3.0 after a
    0-1 s run (u1 = 2 Gain1.y + 3). The file says SSP version 2.0."""
    system, experiment = imported("LinearTransformation")
    assert (experiment.start_time, experiment.stop_time, experiment.step_size) == (0.0, 1.0,
                                                                                   None)
    assert value(system, "Gain1", "y") == 0.0
    assert value(system, "Add1", "u1") == 3.0


def test_top_level_parameters_give_omsimulators_numbers() -> None:
    """OMSimulator's toplevelparameter1.lua prints addP.k1 = -200 and addP.k2 = -300: the
    root's root.ssv wins over the component's addp.ssv (10 and 20); Input_cref = -20 is a
    value on the system's own input, connected to nothing. The step is OMSimulator's
    FixedStepMaster annotation."""
    system, experiment = imported("toplevelparameter1")
    assert experiment.step_size == 0.001
    assert system.components["addP"].user_parameters() == {"k1": -200.0, "k2": -300.0}
    assert value(system, "addP", "k1") == -200.0


def test_values_on_system_connectors_drive_what_they_connect_to() -> None:
    """OMSimulator's import_export_parameters1.lua: after initialization addP.k1 = k_cref = 30
    (not the 10 bound to addP.k1 itself) and addI.k2 = T_cref = 20: a value on a system
    connector drives its connection. Input_cref = -20 in the .ssv drives addP.u1 (the script
    sets -3.7 first), so addP.y = k1 u1 + k2 u2 = 30 * -20 + -1 * 0 = -600. foo.F_cref is a
    connector of the empty subsystem foo: its value drives nothing."""
    system, _ = imported("import_export_parameters1")
    assert value(system, "addP", "k1") == 30.0
    assert value(system, "addP", "k2") == -1.0
    assert value(system, "addP", "u1") == -20.0
    assert value(system, "addP", "y") == -600.0
    assert value(system, "addI", "k2") == 20.0
    assert value(system, "addI", "k3") == 1.0  # the FMU's own start: nothing binds it


def test_an_inline_mapping_onto_system_connectors_loads_without_complaint() -> None:
    """importParameterMappingInline binds values (one source mapped to several targets) to
    connectors of systems that hold no component: nothing to warn about but OMSimulator's
    own annotations."""
    path = available_samples() / "omsimulator/importParameterMappingInline/SystemStructure.ssd"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        system = read(path).system
    assert list(system.components) == []
    assert [str(w.message).split(" is not supported")[0] for w in caught] == [
        "annotation type 'org.openmodelica'"]


def read_quietly(path: Path) -> Any:
    from syssimx.system_files import read_system_file

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return read_system_file(path)


def test_libcosims_linear_transformation_ssd() -> None:
    """Two .ssv files bind identity1.realIn, 2 then 4: the SSP standard gives the later binding
    priority (libcosim instead takes the first as its default parameter set and the second as
    a named alternative, so its own test expects 2); identity2.realIn = 1.3 identity1.realOut
    + 50 = 55.2 (the identity FMU's realOut is its realIn)."""
    imported = read_quietly(available_samples() / "libcosim/ssp/linear_transformation/"
                            "SystemStructure.ssd")
    system = imported.system
    assert system.components["identity1"].input_start("realIn") == 4.0
    system.initialize(0.0)
    system.run(0.0, 0.3, 0.1)
    assert value(system, "identity1", "realOut") == 4.0
    assert value(system, "identity2", "realIn") == pytest.approx(55.2, rel=1e-15)


CRANE_CONNECTIONS = (
    {("KnuckleBoomCrane", f"Act_Limits[{i}]", "CraneController", f"Act_Limits[{i}]")
     for i in (1, 2, 3)}
    | {("CraneController", f"p_Crane.e[{i}]", "KnuckleBoomCrane", f"p_Crane.e[{i}]")
       for i in (1, 2, 3)}
    | {("KnuckleBoomCrane", f"p_Crane.f[{i}]", "CraneController", f"p_Crane.f[{i}]")
       for i in (1, 2, 3)})


def test_libcosims_crane_variable_groups() -> None:
    """OspSystemStructure_Bond.xml joins the groups of the crane's OspModelDescription files
    (the controller's beside the structure, the crane's beside its FMU) element by element,
    the nested Force and LinearVelocity groups of the linear mechanical port included, each
    from the side whose variable is an output; the simulators' stepSize is named once."""
    from syssimx.osp import OSPWarning
    from syssimx.osp import read as read_osp

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        imported = read_osp(available_samples() / "libcosim/msmi/OspSystemStructure_Bond.xml")
    assert [str(w.message).split(" is not")[0] for w in caught
            if w.category is OSPWarning] == [
        "a simulator's own stepSize (libcosim steps it every stepSize/BaseStepSize base "
        "steps)"]
    system = imported.system
    assert set(system.components) == {"CraneController", "KnuckleBoomCrane", "TrueIdentity",
                                      "OneIdentity"}
    assert {c.key() for c in system.connections} == CRANE_CONNECTIONS
    assert system.components["CraneController"].user_parameters() == {"cl1_min": 2.2,
                                                                      "cl1_max": 3.8}
    system.initialize(0.0)
    result = system.run(0.0, 0.001, 1e-4)
    assert len(result["KnuckleBoomCrane"][0]) == 11
