"""String variables in FMI 1.0, 2.0 and 3.0: parameters and start values set from Python,
YAML, SSV and OSP files, and libcosim's quarter truck, whose two FMUs are set a String
parameter, against libcosim's own run of it.

- FMI 1.0: libcosim's identity.fmu echoes its String input on its String output; a copy
  whose String variable is a parameter (FMI 1.0: variability "parameter") echoes that.
- FMI 2.0: the Reference FMUs' Feedthrough (a String input and output); the quarter truck's
  Chassis and Wheel (String parameters: solverType, which picks the FMU's integrator), the
  Chassis alone equal to FMPy for each solverType.
- FMI 3.0: the Reference FMUs' Feedthrough, String and Binary (see also test_fmi3_import).
- String and Binary ports connected and recorded (object arrays of texts and bytes).
"""

from __future__ import annotations

import re
import shutil
import zipfile
from pathlib import Path

import numpy as np
import pytest
from coupling_samples import coupling_samples_root
from fmpy import simulate_fmu
from reference_root import reference_root
from samples_root import samples_root
from syssimx import Connection, FMUComponent, JacobiAlgorithm, System
from syssimx.cli import main
from syssimx.errors import ConfigurationError
from syssimx.osp import read as read_osp
from syssimx.ssp import read as read_ssp
from syssimx.system.loader import build_system

FEEDTHROUGH2 = reference_root() / "fmi2" / "Feedthrough.fmu"
FEEDTHROUGH3 = reference_root() / "fmi3" / "Feedthrough.fmu"
TRUCK = coupling_samples_root() / "quarter_truck"

# libcosim's values of the quarter truck after every 100th step of 1e-4 s, up to 0.1 s, with
# its fixed-step algorithm (the file with <Algorithm>fixedStep and no <EccoConfiguration>;
# solverType = "Euler" and timeStep = 1e-5 in both FMUs, as the file sets): libcosimpy 0.0.6,
# benchmarks/quarter_truck_vs_libcosim.py. Columns: chassis.position, chassis.velocity,
# wheel.position, wheel.velocity, wheel.out_spring_damper_f.
TRUCK_SIGNALS = [("chassis", "position"), ("chassis", "velocity"), ("wheel", "position"),
                 ("wheel", "velocity"), ("wheel", "out_spring_damper_f")]
LIBCOSIM_TRUCK = np.array([
    (0.00014585442304104764, 0.043086964860894125, 0.01670171822945683, 3.0991332626843358,
     -3302.4748331264213),
    (0.001081695917595274, 0.15178619221752793, 0.05600268338547209, 4.439236699852173,
     -5111.626522252618),
    (0.0032556921663989507, 0.2831395000071802, 0.09930596134903895, 3.949008763745468,
     -5108.7930980092315),
    (0.0066777803274003815, 0.3953987260466727, 0.13079681756981976, 2.209850795570792,
     -3679.230296963926),
    (0.01100897014545981, 0.4622598183473265, 0.1423204027640682, 0.10727233747920531,
     -1617.4498374075886),
    (0.015751834688024338, 0.4785344544412009, 0.13450105350295272, -1.5453564154656594,
     240.84838414439855),
    (0.020453255180253063, 0.45720627349080534, 0.11455635011345237, -2.2736076690208087,
     1318.6603815767123),
    (0.024846160278057472, 0.420827260823353, 0.09230739788552014, -2.031067758685382,
     1440.3331178812964),
    (0.028894647472122018, 0.3915163334187053, 0.07617774272357411, -1.1195326855544876,
     802.6078961984759),
    (0.032748471535321115, 0.383353007069662, 0.07057546609613925, -0.005950230653820458,
     -177.401782882394),
])


def needs(path: Path) -> Path:
    if not path.is_file():
        pytest.skip(f"{path} is absent")
    return path


def identity() -> Path:
    return needs(samples_root() / "libcosim" / "fmi1" / "identity.fmu")


def fixed_step_truck(folder: Path) -> Path:
    """The quarter truck copied, its OSP file set to libcosim's fixed step (the FMUs and the
    initial values unchanged)."""
    needs(TRUCK / "OspSystemStructure.xml")
    shutil.copytree(TRUCK, folder)
    path = folder / "OspSystemStructure.xml"
    text = path.read_text().replace("<Algorithm>ecco</Algorithm>",
                                    "<Algorithm>fixedStep</Algorithm>")
    path.write_text(re.sub(r"\s*<EccoConfiguration>.*?</EccoConfiguration>", "", text,
                           flags=re.DOTALL))
    return path


def truck_run(path: Path) -> np.ndarray:
    system = read_osp(path).system
    system.set_algorithm(JacobiAlgorithm())
    system.initialize(0.0)
    result = system.run(0.0, 0.1, 1e-4)
    return np.array([result[c][1][v][1:] for c, v in TRUCK_SIGNALS]).T


# ---------------------------------------------------------------- FMI 2.0


def test_a_string_parameter_of_an_fmi2_fmu_is_set_from_python():
    chassis = FMUComponent("chassis", needs(TRUCK / "Chassis.fmu"))
    assert chassis.parameters["solverType"] == "VRK2"  # the modelDescription's start
    chassis.set_parameters(solverType="Euler")
    assert chassis.parameters["solverType"] == "Euler"
    system = System("one")
    system.add_component(chassis)
    system.initialize(0.0)
    vr = chassis.info.parameters["solverType"].value_reference
    assert chassis.instance.getString([vr]) == ["Euler"]


def test_a_string_parameter_refuses_a_number():
    chassis = FMUComponent("chassis", needs(TRUCK / "Chassis.fmu"))
    with pytest.raises(ConfigurationError) as info:
        chassis.set_parameters(solverType=3)
    assert str(info.value) == "chassis.solverType: port 'solverType' is STRING; got int"


def test_an_fmi2_string_input_is_set_and_its_output_read_back():
    system = System("texts")
    feedthrough = FMUComponent("F", needs(FEEDTHROUGH2))
    system.add_component(feedthrough)
    assert feedthrough.parameters["String_input"] == "Set me!"
    feedthrough.set_parameters(String_input="grüße")
    system.initialize(0.0)
    system.run(0.0, 0.2, 0.1)
    assert feedthrough.get_state()["String_output"]["value"] == "grüße"


def test_the_quarter_truck_at_a_fixed_step_equals_libcosim(tmp_path: Path):
    ours = truck_run(fixed_step_truck(tmp_path / "truck"))
    np.testing.assert_allclose(ours[99::100], LIBCOSIM_TRUCK, rtol=0, atol=1e-9)


def test_the_quarter_truck_depends_on_its_string_parameters(tmp_path: Path):
    """Without solverType = "Euler" (the FMUs' own VRK2) the numbers differ: the String
    values reach the FMUs."""
    path = fixed_step_truck(tmp_path / "truck")
    path.write_text(re.sub(r"\s*<InitialValue variable=\"solverType\">.*?</InitialValue>",
                           "", path.read_text(), flags=re.DOTALL))
    ours = truck_run(path)
    assert np.abs(ours[99::100] - LIBCOSIM_TRUCK).max() > 1e-6


def test_the_quarter_truck_runs_unchanged_with_its_own_settings(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    out = tmp_path / "truck.csv"
    assert main(["run", str(needs(TRUCK / "OspSystemStructure.xml")), "--tf", "0.1",
                 "-o", str(out)]) == 0
    assert "Completed" in capsys.readouterr().out
    assert out.stat().st_size > 0


def test_a_string_parameter_is_set_from_yaml(tmp_path: Path):
    description = tmp_path / "truck.yaml"
    description.write_text(
        "system: {name: chassis alone}\n"
        "components:\n"
        f"  - name: chassis\n    fmu: {needs(TRUCK / 'Chassis.fmu')}\n"
        "    parameters: {solverType: Euler, timeStep: 1.0e-5}\n")
    system = build_system(description)
    chassis = system.components["chassis"]
    assert chassis.parameters["solverType"] == "Euler"
    system.initialize(0.0)
    vr = chassis.info.parameters["solverType"].value_reference
    assert chassis.instance.getString([vr]) == ["Euler"]


def test_a_string_parameter_is_set_from_an_ssv(tmp_path: Path):
    folder = tmp_path / "ssp"
    folder.mkdir()
    shutil.copy(needs(FEEDTHROUGH2), folder / "Feedthrough.fmu")
    (folder / "values.ssv").write_text(
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<ssv:ParameterSet xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameter'
        'Values" version="1.0" name="values"><ssv:Parameters>'
        '<ssv:Parameter name="String_input"><ssv:String value="from SSV"/></ssv:Parameter>'
        '</ssv:Parameters></ssv:ParameterSet>\n')
    (folder / "SystemStructure.ssd").write_text(
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<ssd:SystemStructureDescription xmlns:ssd="http://ssp-standard.org/SSP1/SystemStruct'
        'ureDescription" xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon" '
        'version="1.0" name="texts"><ssd:System name="texts"><ssd:Elements>'
        '<ssd:Component name="F" source="Feedthrough.fmu"><ssd:Connectors>'
        '<ssd:Connector name="String_input" kind="input"><ssc:String/></ssd:Connector>'
        '</ssd:Connectors><ssd:ParameterBindings><ssd:ParameterBinding '
        'source="values.ssv"/></ssd:ParameterBindings></ssd:Component>'
        '</ssd:Elements></ssd:System></ssd:SystemStructureDescription>\n')
    system = read_ssp(folder / "SystemStructure.ssd").system
    system.initialize(0.0)
    system.run(0.0, 0.1, 0.1)
    assert system.components["F"].get_state()["String_output"]["value"] == "from SSV"


# ---------------------------------------------------------------- FMI 1.0


def test_an_fmi1_string_input_is_set_and_its_output_read_back():
    system = System("texts")
    component = FMUComponent("I", identity())
    system.add_component(component)
    assert component.info.parameters["stringIn"].fmi_type == "String"
    component.set_parameters(stringIn="hello FMI 1.0")
    system.initialize(0.0)
    system.run(0.0, 0.2, 0.1)
    assert component.get_state()["stringOut"]["value"] == "hello FMI 1.0"


def test_an_fmi1_string_parameter_is_set(tmp_path: Path):
    """identity.fmu's String variable declared an FMI 1.0 parameter (variability "parameter"):
    the same binary echoes it on stringOut."""
    path = tmp_path / "identity.fmu"
    with zipfile.ZipFile(identity()) as source, zipfile.ZipFile(path, "w") as target:
        for item in source.infolist():
            data = source.read(item)
            if item.filename == "modelDescription.xml":
                data = data.replace(
                    b'name="stringIn"   valueReference="0" variability="discrete" '
                    b'causality="input"',
                    b'name="label"      valueReference="0" variability="parameter" '
                    b'causality="internal"')
                assert b'name="label"' in data
            target.writestr(item, data)
    component = FMUComponent("I", path)
    parameter = component.info.parameters["label"]
    assert (parameter.fmi_type, parameter.start) == ("String", "")
    component.set_parameters(label="a parameter")
    system = System("texts")
    system.add_component(component)
    system.initialize(0.0)
    assert component.get_state()["stringOut"]["value"] == "a parameter"


# ---------------------------------------------------------------- FMI 3.0


def test_an_fmi3_string_parameter_is_set_from_python():
    system = System("texts")
    feedthrough = FMUComponent("F", needs(FEEDTHROUGH3))
    system.add_component(feedthrough)
    feedthrough.set_parameters(String_input="drei")
    system.initialize(0.0)
    system.run(0.0, 0.1, 0.1)
    assert feedthrough.get_state()["String_output"]["value"] == "drei"


# ---------------------------------------------------------------- String ports


def feedthrough_pair(path: Path) -> tuple[System, FMUComponent]:
    """A.String_output -> B.String_input of two Feedthrough FMUs, A's input set to "first"."""
    system = System("texts")
    a = FMUComponent("A", needs(path))
    system.add_component(a)
    system.add_component(FMUComponent("B", path))
    a.set_inputs({"String_input": "first"})
    system.add_connection(Connection("A", "String_output", "B", "String_input"))
    system.set_algorithm(JacobiAlgorithm())
    system.initialize(0.0)
    return system, a


@pytest.mark.parametrize("path", [FEEDTHROUGH2, FEEDTHROUGH3], ids=["fmi2", "fmi3"])
def test_string_outputs_are_recorded_and_connected(path: Path):
    """Recorded as object arrays of texts; a new input value reaches the connected FMU one
    step later (Jacobi), as a number would."""
    system, a = feedthrough_pair(path)
    system.run(0.0, 0.2, 0.1)
    a.set_inputs({"String_input": "second"})
    result = system.run(0.2, 0.4, 0.1)
    t, a_values = result["A"]
    _, b_values = result["B"]
    np.testing.assert_allclose(t, [0.0, 0.1, 0.2, 0.3, 0.4], atol=1e-12)
    assert a_values["String_output"].dtype == object
    assert a_values["String_output"].tolist() == ["first"] * 3 + ["second"] * 2
    assert b_values["String_output"].tolist() == ["first"] * 4 + ["second"]
    assert system.components["B"].inputs["String_input"].raw() == "second"


def test_fmi1_string_ports_are_recorded_and_connected():
    system = System("texts")
    first = FMUComponent("I1", identity())
    system.add_component(first)
    system.add_component(FMUComponent("I2", identity()))
    first.set_inputs({"stringIn": "one point zero"})
    system.add_connection(Connection("I1", "stringOut", "I2", "stringIn"))
    system.initialize(0.0)
    result = system.run(0.0, 0.2, 0.1)
    assert result["I1"][1]["stringOut"].tolist() == ["one point zero"] * 3
    assert result["I2"][1]["stringOut"].tolist()[-1] == "one point zero"


def test_a_string_connects_to_a_string_only():
    system = System("texts")
    system.add_component(FMUComponent("A", needs(FEEDTHROUGH2)))
    system.add_component(FMUComponent("B", FEEDTHROUGH2))
    with pytest.raises(ConfigurationError) as info:
        system.add_connection(Connection("A", "String_output", "B", "Float64_continuous_input"))
    assert str(info.value) == ("A.String_output -> B.Float64_continuous_input: a STRING "
                               "output cannot drive a REAL input")
    with pytest.raises(ConfigurationError) as info:
        system.add_connection(Connection("A", "Float64_continuous_output", "B", "String_input"))
    assert str(info.value) == ("A.Float64_continuous_output -> B.String_input: a REAL output "
                               "cannot drive a STRING input")


def test_an_isolated_fmu_runs_without_its_string_ports():
    """The host process that runs an FMU apart forwards no String calls: its String inputs and
    outputs are no ports there, and the rest of the FMU runs as before."""
    system = System("isolated")
    feedthrough = FMUComponent("F", needs(FEEDTHROUGH2), isolated=True)
    assert "String_output" not in feedthrough.output_specs
    assert "String_input" not in feedthrough.input_specs
    system.add_component(feedthrough)
    feedthrough.set_inputs({"Float64_continuous_input": 2.5})
    system.initialize(0.0)
    result = system.run(0.0, 0.2, 0.1)
    assert result["F"][1]["Float64_continuous_output"].tolist() == [2.5, 2.5, 2.5]


def test_fmi3_binary_ports_are_recorded_and_connected(tmp_path: Path):
    """Binary values are bytes (NUL and 0xff included), recorded as object arrays of bytes and
    written to CSV in hex, as FMI writes a Binary start."""
    system = System("bytes")
    a = FMUComponent("A", needs(FEEDTHROUGH3))
    system.add_component(a)
    system.add_component(FMUComponent("B", FEEDTHROUGH3))
    assert a.input_start("Binary_input") != a.input_start("Binary_input")  # NaN: not set
    a.set_inputs({"Binary_input": b"\x00\xffab"})
    system.add_connection(Connection("A", "Binary_output", "B", "Binary_input"))
    system.set_algorithm(JacobiAlgorithm())
    system.initialize(0.0)
    result = system.run(0.0, 0.2, 0.1)
    assert result["A"][1]["Binary_output"].tolist() == [b"\x00\xffab"] * 3
    assert result["B"][1]["Binary_output"].tolist() == [b"\x00\xffab"] * 3
    assert system.components["B"].inputs["Binary_input"].raw() == b"\x00\xffab"
    out = result.to_csv(tmp_path / "bytes.csv", component="A")
    assert "00ff6162" in out.read_text()
    with pytest.raises(ConfigurationError) as info:
        system.add_connection(Connection("A", "String_output", "B", "Binary_input"))
    assert str(info.value).endswith("a STRING output cannot drive a BINARY input")


def test_a_string_parameter_is_no_port():
    system = System("texts")
    system.add_component(FMUComponent("wheel", needs(TRUCK / "Wheel.fmu")))
    system.add_component(FMUComponent("chassis", TRUCK / "Chassis.fmu"))
    with pytest.raises(ConfigurationError) as info:
        system.add_connection(Connection("wheel", "position", "chassis", "solverType"))
    assert "'chassis' has no input 'solverType' (it is a String variable: set it with " \
        "set_parameters, read it with get_state; it cannot be connected)" in str(info.value)


def test_string_ports_step_on_several_threads():
    """FMUs stepping on worker threads add texts to one table: every text of every member
    arrives intact and numbered once."""
    system = System("threads")
    members = [FMUComponent(f"F{k}", needs(FEEDTHROUGH2)) for k in range(8)]
    for k, member in enumerate(members):
        system.add_component(member)
        member.set_inputs({"String_input": f"member {k}"})
    system.set_algorithm(JacobiAlgorithm(threads=4))
    system.initialize(0.0)
    result = system.run(0.0, 0.5, 0.01)
    for k in range(8):
        assert set(result[f"F{k}"][1]["String_output"].tolist()) == {f"member {k}"}


def test_a_string_parameter_gives_fmpys_numbers():
    """The quarter truck's Chassis alone under a constant force, its integrator chosen by the
    String parameter solverType: FMPy's numbers on the same grid for each choice (bit for bit),
    and the choices differ (Euler at 1e-5 s against the FMU's default VRK2)."""
    path = str(needs(TRUCK / "Chassis.fmu"))
    positions = {}
    for solver in ("Euler", "VRK2"):
        reference = simulate_fmu(path, stop_time=0.1, output_interval=1e-3, step_size=1e-3,
                                 start_values={"force": 1000.0, "solverType": solver,
                                               "timeStep": 1e-5},
                                 output=["position", "velocity"])
        chassis = FMUComponent("chassis", path)
        chassis.set_parameters(solverType=solver, timeStep=1e-5)
        chassis.set_inputs({"force": 1000.0})
        system = System("chassis alone")
        system.add_component(chassis)
        system.initialize(0.0)
        _, values = system.run(0.0, 0.1, 1e-3)["chassis"]
        for name in ("position", "velocity"):
            np.testing.assert_array_equal(values[name], reference[name])
        positions[solver] = values["position"][-1]
    assert abs(positions["Euler"] - positions["VRK2"]) > 1e-7
