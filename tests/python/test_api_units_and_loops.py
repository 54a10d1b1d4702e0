"""Units at the boundary (FMI unit strings, declared types, conversions on connections),
FMU feedthrough from ModelStructure, and algebraic loops of declared feedthrough."""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np
import pytest
from syssimx import (
    AlgebraicLoopError,
    Connection,
    CoSimComponent,
    GaussSeidelAlgorithm,
    PortSpec,
    PortType,
    System,
    units,
)
from syssimx.fmu.info import read_fmu

DESCRIPTION = """<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="Typed" guid="{typed}">
  <CoSimulation modelIdentifier="typed" canGetAndSetFMUstate="true"/>
  <UnitDefinitions><Unit name="N.m"/><Unit name="rad"/><Unit name="kg.m2"/></UnitDefinitions>
  <TypeDefinitions>
    <SimpleType name="Torque"><Real unit="N.m"/></SimpleType>
    <SimpleType name="Angle"><Real unit="rad"/></SimpleType>
  </TypeDefinitions>
  <ModelVariables>
    <ScalarVariable name="tau" valueReference="0" causality="input" variability="continuous">
      <Real declaredType="Torque" start="1.5"/></ScalarVariable>
    <ScalarVariable name="gain" valueReference="1" causality="input" variability="continuous">
      <Real start="2"/></ScalarVariable>
    <ScalarVariable name="phi" valueReference="2" causality="output" variability="continuous">
      <Real declaredType="Angle"/></ScalarVariable>
    <ScalarVariable name="both" valueReference="3" causality="output" variability="continuous">
      <Real/></ScalarVariable>
    <ScalarVariable name="none" valueReference="4" causality="output" variability="continuous">
      <Real/></ScalarVariable>
    <ScalarVariable name="J" valueReference="5" causality="parameter" variability="tunable">
      <Real unit="kg.m2" start="0.5"/></ScalarVariable>
    <ScalarVariable name="n" valueReference="6" causality="parameter" variability="fixed">
      <Integer start="3"/></ScalarVariable>
    <ScalarVariable name="R" valueReference="7" causality="output" variability="continuous">
      <Real unit="Ohm"/></ScalarVariable>
    <ScalarVariable name="odd" valueReference="8" causality="output" variability="continuous">
      <Real unit="bogus_unit"/></ScalarVariable>
  </ModelVariables>
  <ModelStructure>
    <Outputs>
      <Unknown index="3" dependencies="1"/>
      <Unknown index="4"/>
      <Unknown index="5" dependencies=""/>
    </Outputs>
  </ModelStructure>
</fmiModelDescription>
"""


@pytest.fixture
def typed_fmu(tmp_path: Path) -> Path:
    path = tmp_path / "typed.fmu"
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("modelDescription.xml", DESCRIPTION)
        archive.writestr("binaries/linux64/typed.so", "")
    return path


def test_units_inherited_from_declared_types(typed_fmu: Path):
    info = read_fmu(typed_fmu)
    assert info.input_specs["tau"].unit == "N.m"
    assert info.output_specs["phi"].unit == "rad"
    assert info.input_specs["gain"].unit is None
    assert info.parameters["J"].unit == "kg.m2" and info.parameters["J"].tunable
    assert info.parameters["n"].type == PortType.INT and info.parameters["n"].start == 3


def test_feedthrough_from_model_structure(typed_fmu: Path):
    info = read_fmu(typed_fmu)
    # an <Unknown> without dependencies depends on every input; an empty list on none
    assert info.feedthrough == {"phi": {"tau"}, "both": {"tau", "gain"}, "none": set(),
                                "R": {"tau", "gain"}, "odd": {"tau", "gain"}}


def test_units_pint_cannot_read_are_mended_or_dropped(typed_fmu: Path,
                                                       caplog: pytest.LogCaptureFixture):
    info = read_fmu(typed_fmu)
    assert info.output_specs["R"].unit == "ohm"
    assert info.output_specs["odd"].unit is None
    assert caplog.messages == ["typed.fmu: unit 'bogus_unit' of variable 'odd' is unknown to "
                               "pint; dropped (those ports carry no unit)"]


@pytest.mark.parametrize(("fmi", "pint_unit"), [
    ("m/s2", "meter / second ** 2"), ("kg.m2", "kilogram * meter ** 2"),
    ("N.m", "meter * newton"), ("rad/s", "radian / second"), ("s-1", "1 / second"),
    ("1", "dimensionless"), ("N.m.s/rad", "meter * newton * second / radian"),
])
def test_fmi_unit_strings_map_to_pint(fmi: str, pint_unit: str):
    assert str(units.to_unit(fmi)) == pint_unit


def test_conversion_scale_and_offset():
    assert units.conversion("m", "cm") == pytest.approx((100.0, 0.0))
    assert units.conversion("degC", "K") == pytest.approx((1.0, 273.15))
    assert units.conversion(None, "m") == (1.0, 0.0)


class Constant(CoSimComponent):
    def __init__(self, name: str, value: float, unit: str):
        super().__init__(name)
        self.value = value
        self.output_specs["y"] = PortSpec("y", PortType.REAL, "out", unit)

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _update_output_states(self, t=None, event_names=None) -> None:
        self.outputs["y"].set(self.value, t)


class Probe(CoSimComponent):
    """Copies its input to its output, with a declared feedthrough."""

    def __init__(self, name: str, unit: str | None, gain: float = 1.0, offset: float = 0.0):
        super().__init__(name)
        self.gain, self.offset = gain, offset
        self.input_specs["u"] = PortSpec("u", PortType.REAL, "in", unit)
        self.output_specs["y"] = PortSpec("y", PortType.REAL, "out", unit)
        self.direct_feedthrough = {"y": {"u"}}

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _compute(self) -> float:
        return self.gain * self.inputs["u"].raw() + self.offset

    def _update_output_states(self, t=None, event_names=None) -> None:
        self.outputs["y"].set(self._compute(), t)

    def evaluate_outputs(self, inputs, t=None):
        for name, value in inputs.items():
            self.inputs[name].set(value, t)
        return {"y": self._compute()}


def test_connection_converts_metres_to_centimetres():
    system = System("units")
    system.add_component(Constant("Src", 1.5, "m"))
    system.add_component(Probe("Dst", "cm"))
    system.add_connection(Connection("Src", "y", "Dst", "u"))
    system.initialize(0.0)
    _, data = system.run(0.0, 0.2, 0.1)["Dst"]
    np.testing.assert_allclose(data["y"], 150.0, rtol=1e-15)
    assert system.components["Dst"].inputs["u"].get().to("m").magnitude == pytest.approx(1.5)


def test_connection_converts_celsius_to_kelvin_with_offset():
    system = System("offset")
    system.add_component(Constant("Src", 20.0, "degC"))
    system.add_component(Probe("Dst", "K"))
    system.add_connection(Connection("Src", "y", "Dst", "u"))
    system.initialize(0.0)
    _, data = system.run(0.0, 0.1, 0.1)["Dst"]
    np.testing.assert_allclose(data["y"], 293.15, rtol=1e-15)


def loop_system(gain: float) -> System:
    # y = 0.5 z + 1, z = gain * y  ->  y = 1 / (1 - 0.5 gain)
    system = System("loop")
    system.add_component(Probe("A", None, gain=0.5, offset=1.0))
    system.add_component(Probe("B", None, gain=gain))
    system.add_connection(Connection("A", "y", "B", "u"))
    system.add_connection(Connection("B", "y", "A", "u"))
    system.set_algorithm(GaussSeidelAlgorithm(tolerance=1e-12, max_iter=200))
    return system


def test_declared_feedthrough_loop_is_solved_at_every_point():
    system = loop_system(gain=1.0)
    system.initialize(0.0)
    result = system.run(0.0, 0.3, 0.1)
    np.testing.assert_allclose(result["A"][1]["y"], 2.0, atol=1e-10)
    np.testing.assert_allclose(result["B"][1]["y"], 2.0, atol=1e-10)
    assert result.statistics.loop_solves >= 3


def test_loop_with_unstable_fixed_point_is_still_solved():
    system = loop_system(gain=4.0)  # y = 2 y + 1: slope 2, solution y = -1
    system.initialize(0.0)
    np.testing.assert_allclose(system.run(0.0, 0.2, 0.1)["A"][1]["y"], -1.0, atol=1e-9)


def test_loop_without_solution_is_a_clear_error():
    system = loop_system(gain=2.0)  # y = y + 1 has no solution
    system.set_algorithm(GaussSeidelAlgorithm(tolerance=1e-12, max_iter=20))
    with pytest.raises(AlgebraicLoopError, match="loop"):
        system.initialize(0.0)
