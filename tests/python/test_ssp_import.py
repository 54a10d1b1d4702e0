"""An SSP written by hand: a nested system, a LinearTransformation, a unit conversion m -> cm,
a signal dictionary, parameters inline and from an .ssv with an .ssm mapping, a default
experiment with the OSP step annotation. Its numbers are derived by hand and match the same
system built in Python."""

from __future__ import annotations

import warnings
import zipfile
from pathlib import Path

import numpy as np
import pytest
from ssp_archive import reference_fmu, ssd, write_ssp
from syssimx import Connection, FMUComponent, System, fmus
from syssimx.ssp import read

PLANT = """
<ssd:System name="Plant">
  <ssd:Connectors>
    <ssd:Connector name="position" kind="output"><ssc:Real unit="m"/></ssd:Connector>
  </ssd:Connectors>
  <ssd:Elements>
    <ssd:Component name="Mass" source="resources/sliding_mass.fmu">
      <ssd:Connectors>
        <ssd:Connector name="x" kind="output"><ssc:Real unit="m"/></ssd:Connector>
      </ssd:Connectors>
      <ssd:ParameterBindings>
        <ssd:ParameterBinding>
          <ssd:ParameterValues>
            <ssv:ParameterSet version="1.0" name="friction">
              <ssv:Parameters>
                <ssv:Parameter name="mu"><ssv:Real value="0"/></ssv:Parameter>
                <ssv:Parameter name="x0"><ssv:Real value="7" unit="m"/></ssv:Parameter>
              </ssv:Parameters>
            </ssv:ParameterSet>
          </ssd:ParameterValues>
        </ssd:ParameterBinding>
      </ssd:ParameterBindings>
    </ssd:Component>
  </ssd:Elements>
  <ssd:Connections>
    <ssd:Connection startElement="Mass" startConnector="x" endConnector="position"/>
  </ssd:Connections>
</ssd:System>"""

ROOT = f"""
<ssd:System name="Line">
  <ssd:ParameterBindings>
    <ssd:ParameterBinding source="parameters/start.ssv">
      <ssd:ParameterMapping source="parameters/start.ssm"/>
    </ssd:ParameterBinding>
  </ssd:ParameterBindings>
  <ssd:Elements>
    {PLANT}
    <ssd:Component name="Sum" source="resources/sum.fmu">
      <ssd:Connectors>
        <ssd:Connector name="u" kind="input"><ssc:Real unit="cm"/></ssd:Connector>
        <ssd:Connector name="y" kind="output"><ssc:Real unit="m"/></ssd:Connector>
      </ssd:Connectors>
      <ssd:ParameterBindings>
        <ssd:ParameterBinding>
          <ssd:ParameterValues>
            <ssv:ParameterSet version="1.0" name="sum">
              <ssv:Parameters>
                <ssv:Parameter name="b"><ssv:Real value="1"/></ssv:Parameter>
                <ssv:Parameter name="c"><ssv:Real value="0.01"/></ssv:Parameter>
              </ssv:Parameters>
            </ssv:ParameterSet>
          </ssd:ParameterValues>
        </ssd:ParameterBinding>
      </ssd:ParameterBindings>
    </ssd:Component>
    <ssd:Component name="Gain" source="resources/gain.fmu">
      <ssd:Connectors>
        <ssd:Connector name="u" kind="input"><ssc:Real unit="m"/></ssd:Connector>
      </ssd:Connectors>
    </ssd:Component>
    <ssd:SignalDictionaryReference name="bus" dictionary="signals">
      <ssd:Connectors>
        <ssd:Connector name="level" kind="inout"><ssc:Real unit="m"/></ssd:Connector>
      </ssd:Connectors>
    </ssd:SignalDictionaryReference>
  </ssd:Elements>
  <ssd:Connections>
    <ssd:Connection startElement="Plant" startConnector="position" endElement="Sum"
                    endConnector="u">
      <ssc:LinearTransformation factor="2" offset="0.5"/>
    </ssd:Connection>
    <ssd:Connection startElement="Sum" startConnector="y" endElement="bus"
                    endConnector="level"/>
    <ssd:Connection startElement="bus" startConnector="level" endElement="Gain"
                    endConnector="u"/>
  </ssd:Connections>
  <ssd:SignalDictionaries>
    <ssd:SignalDictionary name="signals">
      <ssb:SignalDictionary version="1.0">
        <ssb:DictionaryEntry name="level"><ssc:Real unit="m"/></ssb:DictionaryEntry>
      </ssb:SignalDictionary>
    </ssd:SignalDictionary>
  </ssd:SignalDictionaries>
</ssd:System>"""

EXPERIMENT = """
<ssd:DefaultExperiment startTime="0" stopTime="1">
  <ssd:Annotations>
    <ssc:Annotation type="com.opensimulationplatform">
      <osp:FixedStepAlgorithm xmlns:osp="http://opensimulationplatform.com/SSP/OSPAnnotations"
                              baseStepSize="0.125"/>
    </ssc:Annotation>
  </ssd:Annotations>
</ssd:DefaultExperiment>"""

# x0 = 50 cm (the root's binding wins over the component's 7 m), v0 = 2 * speed by the mapping
SSV = """<?xml version="1.0" encoding="UTF-8"?>
<ssv:ParameterSet xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues"
                  version="1.0" name="start">
  <ssv:Parameters>
    <ssv:Parameter name="Plant.Mass.x0"><ssv:Real value="50" unit="cm"/></ssv:Parameter>
    <ssv:Parameter name="speed"><ssv:Real value="0.5"/></ssv:Parameter>
    <ssv:Parameter name="Gain.k"><ssv:Real value="3"/></ssv:Parameter>
  </ssv:Parameters>
</ssv:ParameterSet>"""

SSM = """<?xml version="1.0" encoding="UTF-8"?>
<ssm:ParameterMapping xmlns:ssm="http://ssp-standard.org/SSP1/SystemStructureParameterMapping"
                      xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon"
                      version="1.0">
  <ssm:MappingEntry source="speed" target="Plant.Mass.v0">
    <ssc:LinearTransformation factor="2"/>
  </ssm:MappingEntry>
</ssm:ParameterMapping>"""

BUNDLED = ("sliding_mass", "sum", "gain")


def hand_written(tmp_path: Path, root: str = ROOT, units: str = "") -> Path:
    return write_ssp(tmp_path / "line.ssp", ssd(root, "line", EXPERIMENT, units),
                     {"parameters/start.ssv": SSV, "parameters/start.ssm": SSM}, BUNDLED)


def python_built() -> System:
    system = System("Line")
    mass = FMUComponent("Plant.Mass", fmus.path("sliding_mass"))
    mass.set_parameters(mu=0.0, x0=0.5, v0=1.0)
    total = FMUComponent("Sum", fmus.path("sum"))
    total.set_parameters(b=1.0, c=0.01)
    gain = FMUComponent("Gain", fmus.path("gain"))
    gain.set_parameters(k=3.0)
    for component in (mass, total, gain):
        system.add_component(component)
    system.add_connection(Connection("Plant.Mass", "x", "Sum", "u", factor=2.0, offset=0.5))
    system.add_connection(Connection("Sum", "y", "Gain", "u"))
    return system


def outputs(system: System, dt: float) -> tuple[np.ndarray, ...]:
    system.initialize(0.0)
    result = system.run(0.0, 1.0, dt)
    t, mass = result["Plant.Mass"]
    return t, mass["x"], result["Sum"][1]["y"], result["Gain"][1]["y"]


def test_the_hand_written_ssp_gives_the_numbers_derived_by_hand(tmp_path: Path) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # everything in it is supported
        imported = read(hand_written(tmp_path))
    assert (imported.experiment.start_time, imported.experiment.stop_time,
            imported.experiment.step_size) == (0.0, 1.0, 0.125)
    system = imported.system
    assert list(system.components) == ["Plant.Mass", "Sum", "Gain"]
    assert system.components["Plant.Mass"].user_parameters() == {"mu": 0.0, "x0": 0.5,
                                                                 "v0": 1.0}
    t, x, y, gain = outputs(system, imported.experiment.step_size)
    np.testing.assert_allclose(x, 0.5 + t, rtol=0, atol=1e-12)
    # Sum.u = 2 * (100 cm/m * x) + 0.5 cm, Sum.y = b - c u = 1 - 0.01 (200 x + 0.5)
    np.testing.assert_allclose(y, 0.995 - 2.0 * x, rtol=0, atol=1e-12)
    # Gain computes y = k u in its doStep from the input set before it: one step behind; at t0
    # from the input given in initialization mode, as it leaves it
    assert gain[0] == pytest.approx(3.0 * y[0], abs=1e-15)
    np.testing.assert_allclose(gain[1:], 3.0 * y[:-1], rtol=0, atol=1e-12)


def test_the_hand_written_ssp_runs_as_the_same_system_built_in_python(tmp_path: Path) -> None:
    imported = read(hand_written(tmp_path)).system
    for a, b in zip(outputs(imported, 0.125), outputs(python_built(), 0.125), strict=True):
        assert np.abs(a - b).max() <= 1e-12


def test_units_defined_in_the_ssd_convert_a_connection(tmp_path: Path) -> None:
    """ssc:Units: a "length_in_cm" unit pint does not know, defined as 0.01 m."""
    units = """<ssd:Units>
      <ssc:Unit name="m"><ssc:BaseUnit m="1"/></ssc:Unit>
      <ssc:Unit name="cm"><ssc:BaseUnit m="1" factor="0.01"/></ssc:Unit>
    </ssd:Units>"""
    imported = read(hand_written(tmp_path, units=units)).system
    connection = imported.connections[0]
    assert (connection.factor, connection.offset, connection.convert_units) == (200.0, 0.5,
                                                                               False)
    _, x, y, _ = outputs(imported, 0.125)
    np.testing.assert_allclose(y, 0.995 - 2.0 * x, rtol=0, atol=1e-12)


def test_suppress_unit_conversion_applies_only_the_transformation(tmp_path: Path) -> None:
    root = ROOT.replace('endConnector="u">', 'endConnector="u" suppressUnitConversion="true">')
    _, x, y, _ = outputs(read(hand_written(tmp_path, root)).system, 0.125)
    np.testing.assert_allclose(y, 1.0 - 0.01 * (2.0 * x + 0.5), rtol=0, atol=1e-12)


def test_a_plain_ssd_refers_to_fmus_beside_it(tmp_path: Path) -> None:
    for name in BUNDLED:
        (tmp_path / "resources").mkdir(exist_ok=True)
        (tmp_path / "resources" / f"{name}.fmu").write_bytes(Path(fmus.path(name)).read_bytes())
    (tmp_path / "parameters").mkdir()
    (tmp_path / "parameters" / "start.ssv").write_text(SSV)
    (tmp_path / "parameters" / "start.ssm").write_text(SSM)
    (tmp_path / "line.ssd").write_text(ssd(ROOT, "line", EXPERIMENT))
    _, x, y, _ = outputs(read(tmp_path / "line.ssd").system, 0.125)
    np.testing.assert_allclose(y, 0.995 - 2.0 * x, rtol=0, atol=1e-12)


@pytest.mark.parametrize("reference", ["BouncingBall", "VanDerPol"])
def test_reference_fmus_run_from_an_ssp_as_fmpy_runs_them(tmp_path: Path,
                                                          reference: str) -> None:
    """An FMU at the archive's root, no connectors declared: the FMU's own variables."""
    from fmpy import simulate_fmu

    fmu = reference_fmu(reference)
    text = ssd(f'<ssd:System name="one"><ssd:Elements><ssd:Component name="{reference}" '
               f'source="{reference}.fmu"/></ssd:Elements></ssd:System>', "one",
               '<ssd:DefaultExperiment startTime="0" stopTime="1"/>')
    path = write_ssp(tmp_path / "one.ssp", text)
    with zipfile.ZipFile(path, "a") as archive:
        archive.write(fmu, f"{reference}.fmu")
    system = read(path).system
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.01)
    _, values = result[reference]
    expected = simulate_fmu(str(fmu), stop_time=1.0, output_interval=0.01)
    first = expected.dtype.names[1]
    assert np.abs(values[first] - expected[first]).max() == 0.0
