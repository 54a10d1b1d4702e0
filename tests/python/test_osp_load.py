"""syssimx.osp: OSP system structures as libcosim reads them build the same System as Python
code (the coupled pendulums of osp_files.py give identical numbers), and what syssimx does not
support or cannot find is named."""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from osp_files import FACTOR, NAMESPACE, OFFSET, python_built, structure, write_osp
from ssp_archive import reference_fmu
from syssimx import GaussSeidelAlgorithm, JacobiAlgorithm, System
from syssimx.cli import main
from syssimx.osp import OSPError, OSPImported, OSPWarning, load, read


def outputs(system: System, tf: float = 0.5) -> dict[str, np.ndarray]:
    system.set_algorithm(GaussSeidelAlgorithm())
    system.initialize(0.0)
    result = system.run(0.0, tf, 0.01)
    return {f"{c}.{v}": result[c][1][v] for c, v in (("P1", "theta"), ("P2", "theta"),
                                                      ("Spring", "tau2"))}


def read_quietly(path: Path, strict: bool = False) -> tuple[OSPImported, list[str]]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        imported = read(path, strict)
    return imported, [str(w.message) for w in caught if w.category is OSPWarning]


def test_an_osp_structure_builds_the_system_python_builds(tmp_path: Path) -> None:
    imported, caught = read_quietly(write_osp(tmp_path))
    assert caught == []
    system = imported.system
    assert system.name == tmp_path.name  # the folder of an OspSystemStructure.xml
    assert (imported.experiment.start_time, imported.experiment.stop_time,
            imported.experiment.step_size, imported.algorithm) == (0.0, 0.5, 0.01, "fixedStep")
    assert type(system.algorithm) is JacobiAlgorithm  # libcosim's fixedStep
    assert sorted(c.key() for c in system.connections) == \
        sorted(c.key() for c in python_built().connections)
    angle = next(c for c in system.connections if c.key() == ("P2", "theta", "Spring",
                                                               "theta2"))
    assert (angle.factor, angle.offset) == (FACTOR, OFFSET)
    assert system.components["Spring"].user_parameters() == {"k": 100.0, "d": 1.0}
    ours, reference = outputs(system), outputs(python_built())
    for name in reference:
        assert np.array_equal(ours[name], reference[name]), name


def test_power_bonds_are_recorded(tmp_path: Path) -> None:
    imported, _ = read_quietly(write_osp(tmp_path))
    assert [(b.name, b.connections) for b in imported.power_bonds] == [
        ("right", ((("P2", "omega"), ("Spring", "omega2")),
                   (("Spring", "tau2"), ("P2", "torque"))))]


def test_a_model_description_beside_the_structure_is_found(tmp_path: Path) -> None:
    imported, caught = read_quietly(write_osp(tmp_path, groups_beside_fmus=False))
    assert caught == [] and len(imported.system.connections) == 6


def test_the_folder_of_a_structure_loads_it(tmp_path: Path) -> None:
    write_osp(tmp_path)
    assert len(load(tmp_path).connections) == 6


ECCO = """<EccoConfiguration>
    <SafetyFactor>0.99</SafetyFactor>
    <StepSize>0.0001</StepSize>
    <MinimumStepSize>0.00001</MinimumStepSize>
    <MaximumStepSize>0.01</MaximumStepSize>
    <RelativeTolerance>1e-6</RelativeTolerance>
  </EccoConfiguration>
</OspSystemStructure>"""


def test_ecco_adapts_the_step_to_the_energy_residual_of_the_power_bonds(tmp_path: Path) -> None:
    """<Algorithm>ecco runs Jacobi with non-iterative step control bounded by the
    <EccoConfiguration>, measuring the energy residual of the power bond `right`."""
    path = write_osp(tmp_path, structure("ecco").replace("</OspSystemStructure>", ECCO))
    imported, caught = read_quietly(path)
    assert imported.algorithm == "ecco" and imported.experiment.step_size == 0.01
    assert imported.ecco == {"SafetyFactor": 0.99, "StepSize": 1e-4, "MinimumStepSize": 1e-5,
                             "MaximumStepSize": 0.01, "RelativeTolerance": 1e-6}
    control = imported.system.algorithm.step_control
    assert type(imported.system.algorithm) is JacobiAlgorithm and not control.rollback
    assert (control.safety, control.initial_step, control.min_step, control.max_step,
            control.rtol) == (0.99, 1e-4, 1e-5, 0.01, 1e-6)
    assert control.error == "energy"
    assert control.power_bonds == ((("Spring", "omega2"), ("P2", "torque")),)
    assert caught == []
    system = imported.system
    system.initialize(0.0)
    statistics = system.run(0.0, 0.1, 0.01).statistics
    # the steps adapted inside the grid: more accepted steps than grid intervals, none rejected
    assert statistics.accepted_steps > 10 and statistics.rejected_steps == 0
    assert statistics.smallest_step < statistics.largest_step <= 0.01 + 1e-12
    read(path, strict=True)  # nothing unsupported


def test_ecco_without_power_bonds_controls_the_coupling_error_with_one_warning(
        tmp_path: Path) -> None:
    text = structure("ecco").replace("</OspSystemStructure>", ECCO)
    path = write_osp(tmp_path, text.replace(' powerBond="right"', ""))
    imported, caught = read_quietly(path)
    assert imported.system.algorithm.step_control.error == "coupling"
    assert len(caught) == 1 and caught[0].startswith("<Algorithm> ecco without power bonds")
    with pytest.raises(OSPError, match=r"ecco without power bonds is not supported \(strict\)"):
        read(path, strict=True)


BOOLEAN_GAIN = ('<Simulator name="G" source="fmus/gain.fmu" stepSize="0.02"><InitialValues>'
                '<InitialValue variable="u"><Integer value="3"/></InitialValue>'
                '</InitialValues></Simulator>')


def test_unsupported_things_are_named_once_each(tmp_path: Path) -> None:
    """A simulator's own stepSize (libcosim's multi-rate stepping) and a Sum function."""
    extra = ('<SignalConnection><Variable simulator="G" name="y"/>'
             '<Signal function="total" name="in[0]"/></SignalConnection>')
    text = structure(extra_simulator=BOOLEAN_GAIN, extra=extra).replace(
        "</Functions>", '<Sum name="total" inputCount="1"/></Functions>')
    path = write_osp(tmp_path, text)
    imported, caught = read_quietly(path)
    assert [m.split(" is not supported")[0] for m in caught] == [
        "a simulator's own stepSize (libcosim steps it every stepSize/BaseStepSize base "
        "steps)", "function <Sum>"]
    assert imported.system.components["G"].input_start("u") == 3.0  # an input's start


@pytest.mark.parametrize(("text", "expected"), [("1", True), ("0", False), ("true", True)])
def test_boolean_initial_values_are_xml_schema_booleans(tmp_path: Path, text: str,
                                                        expected: bool) -> None:
    """The Reference Feedthrough FMU: Boolean_output = Boolean_input."""
    fmu = reference_fmu("Feedthrough")
    (tmp_path / "Feedthrough.fmu").write_bytes(fmu.read_bytes())
    path = tmp_path / "b.xml"
    path.write_text(f'<OspSystemStructure xmlns="{NAMESPACE}" version="0.1"><BaseStepSize>0.1'
                    '</BaseStepSize><Simulators><Simulator name="F" source="Feedthrough.fmu">'
                    '<InitialValues><InitialValue variable="Boolean_input">'
                    f'<Boolean value="{text}"/></InitialValue></InitialValues></Simulator>'
                    '</Simulators></OspSystemStructure>')
    system = load(path)
    system.initialize(0.0)
    system.run(0.0, 0.2, 0.1)
    assert system.components["F"].get_state()["Boolean_output"]["value"] is expected


def test_a_local_proxy_fmu_runs_isolated_and_a_remote_one_is_refused(tmp_path: Path) -> None:
    text = structure(extra_simulator=BOOLEAN_GAIN.replace(
        'source="fmus/gain.fmu" stepSize="0.02"',
        'source="proxyfmu://localhost?file=fmus/gain.fmu"'))
    path = write_osp(tmp_path, text)
    imported, caught = read_quietly(path)
    assert imported.system.components["G"].isolated
    assert caught[0].startswith("a proxy FMU server (proxyfmu://) is not supported and is "
                                f"ignored: {path}: <Simulator 'G'> (line ")
    path.write_text(text.replace("localhost", "sim.example.com"))
    with pytest.raises(OSPError, match=r"is a proxy FMU on the remote host 'sim\.example\.com'"):
        load(path)


def test_a_proxy_fmu_the_isolated_host_cannot_run_runs_in_process(tmp_path: Path) -> None:
    """The host process speaks FMI 2.0: a proxy FMU of FMI 3.0 runs in syssimx's process."""
    from syssimx import fmus

    (tmp_path / "fmus").mkdir()
    (tmp_path / "fmus" / "gain_fmi3.fmu").write_bytes(Path(fmus.path("gain_fmi3")).read_bytes())
    path = tmp_path / "p.xml"
    path.write_text(f'<OspSystemStructure xmlns="{NAMESPACE}" version="0.1"><BaseStepSize>0.1'
                    '</BaseStepSize><Simulators><Simulator name="G" '
                    'source="proxyfmu://localhost?file=fmus/gain_fmi3.fmu"/></Simulators>'
                    '</OspSystemStructure>')
    imported, caught = read_quietly(path)
    assert not imported.system.components["G"].isolated
    assert caught == [f"a proxy FMU server (proxyfmu://) for an FMI 3.0 FMU is not supported "
                      f"and is ignored: {path}: <Simulator 'G'> (line 1): the FMU runs in "
                      "syssimx's process (a host process of syssimx's own runs FMI 2.0 FMUs "
                      "only)"]


@pytest.mark.parametrize(("change", "problem"), [
    (('name="omega2"', 'name="nothing"'),
     r"<VariableConnection> \(line \d+\): 'Spring' \(.*torsion_spring.fmu\) has no input or "
     r"output 'nothing'"),
    (('simulator="Spring" name="left"', 'simulator="Spring" name="right"'),
     r"simulator 'Spring' has no variable group 'right' \(groups: left\)"),
    (('<Variable simulator="P2" name="theta"/>', '<Variable simulator="P3" name="theta"/>'),
     r"simulator 'P3' is not among the <Simulators> \(P1, P2, Spring\)"),
    (('<Signal function="halved" name="out"/>', '<Signal function="halved" name="out2"/>'),
     r"<LinearTransformation 'halved'> \(line \d+\): the function needs a <SignalConnection> "
     "to its signal 'in' and one from 'out'"),
    (('<Real value="100"/>', '<Real value="stiff"/>'),
     r"<InitialValue> \(line \d+\) for 'k': Real value 'stiff' is not a float value"),
    (('<InitialValue variable="k">', '<InitialValue variable="kk">'),
     r"'Spring' \(.*\) has no parameter or input 'kk'"),
    (('<Algorithm>fixedStep', '<Algorithm>fastest'),
     r"<Algorithm> 'fastest' is not one of fixedStep, ecco"),
    (('<BaseStepSize>0.01', '<BaseStepSize>0'), r"<BaseStepSize> 0.0 must be positive"),
])
def test_bad_input_is_an_osp_error_naming_file_and_element(tmp_path: Path,
                                                           change: tuple[str, str],
                                                           problem: str) -> None:
    path = write_osp(tmp_path, structure().replace(*change))
    with pytest.raises(OSPError, match=f"{re.escape(str(path))}: .*{problem}"):
        load(path)


def test_a_file_that_is_not_an_osp_structure(tmp_path: Path) -> None:
    path = tmp_path / "other.xml"
    path.write_text("<MSMI/>")
    with pytest.raises(OSPError, match=re.escape(f"{path}: not an OSP system structure: its "
                                                 "root element is <MSMI>")):
        load(path)


def test_run_and_describe_read_an_osp_structure(tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    path = write_osp(tmp_path)
    assert main(["run", str(path), "--quiet"]) == 0
    assert f"Completed '{tmp_path.name}': t in [0.0, 0.5] s, dt = 0.01 s, algorithm = " \
           "JacobiAlgorithm" in capsys.readouterr().out
    assert main(["describe", str(path)]) == 0
    assert "  Spring.tau2 [N.m] -> P2.torque [N.m]" in capsys.readouterr().out


def test_the_front_ends_are_attributes_of_the_package() -> None:
    """`syssimx.ssp.load` and `syssimx.osp.load` as the documentation writes them, imported on
    first use."""
    import syssimx

    assert syssimx.osp.load is load
    assert syssimx.ssp.load.__module__ == "syssimx.ssp.load"


def test_entities_are_not_resolved(tmp_path: Path) -> None:
    """A structure is data: an external entity is not fetched (its text stays empty)."""
    secret = tmp_path / "secret.txt"
    secret.write_text("0.5")
    path = tmp_path / "e.xml"
    path.write_text(f'<?xml version="1.0"?>\n<!DOCTYPE OspSystemStructure [<!ENTITY step '
                    f'SYSTEM "file://{secret}">]>\n<OspSystemStructure xmlns="{NAMESPACE}" '
                    'version="0.1"><BaseStepSize>&step;</BaseStepSize><Simulators/>'
                    '</OspSystemStructure>')
    with pytest.raises(OSPError, match=re.escape(f"{path}: <BaseStepSize> (line 3): "
                                                 "BaseStepSize '' is not a float value")):
        load(path)
