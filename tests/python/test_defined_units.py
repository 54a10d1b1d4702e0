"""Units defined by their SI base units, whose names are only labels: an SSD's ssc:Units
(OMSimulator writes "[m]" for the metre) and an FMU's own UnitDefinitions where pint does not
know the name. Conversions follow the definitions; the numbers are derived by hand."""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np
import pytest
from ssp_archive import ssd, write_ssp
from syssimx import Connection, FMUComponent, System, fmus
from syssimx.ssp import read

# what OMSimulator writes, plus a millimetre and a Fahrenheit-like degree of our own
LABELS = """<ssd:Units>
  <ssc:Unit name="[m]"><ssc:BaseUnit m="1"/></ssc:Unit>
  <ssc:Unit name="[cm]"><ssc:BaseUnit m="1" factor="0.01"/></ssc:Unit>
  <ssc:Unit name="[mm]"><ssc:BaseUnit m="1" factor="0.001"/></ssc:Unit>
  <ssc:Unit name="[degF]"><ssc:BaseUnit K="1" factor="0.5555555555555556"
                                        offset="255.3722222222222"/></ssc:Unit>
  <ssc:Unit name="[K]"><ssc:BaseUnit K="1"/></ssc:Unit>
</ssd:Units>"""

LINE = """
<ssd:System name="Line">
  <ssd:Elements>
    <ssd:Component name="Mass" source="resources/sliding_mass.fmu">
      <ssd:Connectors>
        <ssd:Connector name="x" kind="output"><ssc:Real unit="[m]"/></ssd:Connector>
      </ssd:Connectors>
      <ssd:ParameterBindings><ssd:ParameterBinding><ssd:ParameterValues>
        <ssv:ParameterSet version="1.0" name="start"><ssv:Parameters>
          <ssv:Parameter name="mu"><ssv:Real value="0"/></ssv:Parameter>
          <ssv:Parameter name="x0"><ssv:Real value="500" unit="[mm]"/></ssv:Parameter>
          <ssv:Parameter name="v0"><ssv:Real value="1"/></ssv:Parameter>
        </ssv:Parameters></ssv:ParameterSet>
      </ssd:ParameterValues></ssd:ParameterBinding></ssd:ParameterBindings>
    </ssd:Component>
    <ssd:Component name="Sum" source="resources/sum.fmu">
      <ssd:Connectors>
        <ssd:Connector name="u" kind="input"><ssc:Real unit="[cm]"/></ssd:Connector>
        <ssd:Connector name="y" kind="output"><ssc:Real unit="[m]"/></ssd:Connector>
      </ssd:Connectors>
    </ssd:Component>
  </ssd:Elements>
  <ssd:Connections>
    <ssd:Connection startElement="Mass" startConnector="x" endElement="Sum" endConnector="u"/>
  </ssd:Connections>
</ssd:System>"""


def test_units_the_ssd_defines_are_read_by_their_definitions(tmp_path: Path) -> None:
    """x0 = 500 [mm] = 0.5 m, so x = 0.5 + t; x reaches Sum.u in [cm] (100 x), and the sum
    FMU gives y = b - c u with its start values b = 0, c = 1."""
    path = write_ssp(tmp_path / "labels.ssp", ssd(LINE, "labels", "", LABELS), None,
                     ("sliding_mass", "sum"))
    system = read(path).system
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.25)
    t, mass = result["Mass"]
    np.testing.assert_allclose(mass["x"], 0.5 + t, rtol=0, atol=1e-12)
    # the sum FMU computes y in its doStep from the input set before it: one step behind
    np.testing.assert_allclose(result["Sum"][1]["y"][1:], -100.0 * mass["x"][:-1], rtol=0,
                               atol=1e-12)


def test_a_label_defined_as_another_quantity_is_still_refused(tmp_path: Path) -> None:
    """The label is read by its definition: "[cm]" defined as a kelvin does not match cm."""
    units = LABELS.replace('name="[cm]"><ssc:BaseUnit m="1"', 'name="[cm]"><ssc:BaseUnit K="1"')
    path = write_ssp(tmp_path / "wrong.ssp", ssd(LINE, "wrong", "", units), None,
                     ("sliding_mass", "sum"))
    with pytest.raises(ValueError, match=r"unit '\[cm\]' does not match the FMU's unit 'cm'"):
        read(path)


def gain_in(tmp_path: Path, label: str, base_unit: str) -> Path:
    """The bundled gain with its unit "m" renamed `label` (unknown to pint) and defined by
    `base_unit` (a BaseUnit element)."""
    path = tmp_path / f"gain_{len(list(tmp_path.iterdir()))}.fmu"
    with zipfile.ZipFile(fmus.path("gain")) as original, zipfile.ZipFile(path, "w") as edited:
        for entry in original.namelist():
            data = original.read(entry)
            if entry == "modelDescription.xml":
                text = data.decode()
                old_definition = '<Unit name="m">\n      <BaseUnit m="1"/>'
                assert old_definition in text and text.count('unit="m"') == 2
                text = text.replace(old_definition, f'<Unit name="{label}">{base_unit}')
                data = text.replace('unit="m"', f'unit="{label}"').encode()
            edited.writestr(entry, data)
    return path


FAHRENHEIT = '<BaseUnit K="1" factor="0.5555555555555556" offset="255.3722222222222"/>'


def test_units_an_fmu_defines_convert_a_connection(tmp_path: Path) -> None:
    """212 in the FMU's "[degF]" is 373.15 in the other FMU's "[K]" (a pure kelvin)."""
    hot = FMUComponent("Hot", str(gain_in(tmp_path, "[degF]", FAHRENHEIT)))
    cold = FMUComponent("Cold", str(gain_in(tmp_path, "[K]", '<BaseUnit K="1"/>')))
    assert cold.input_specs["u"].unit == "K"
    hot.set_inputs({"u": 212.0})
    system = System("s")
    for component in (hot, cold):
        system.add_component(component)
    system.add_connection(Connection("Hot", "y", "Cold", "u"))
    system.initialize(0.0)
    result = system.run(0.0, 0.5, 0.25)
    assert result["Hot"][1]["y"][-1] == 212.0
    assert result["Cold"][1]["y"][-1] == pytest.approx(373.15, abs=1e-9)
    # the definition, not the label: 32 [degF] read as a pint quantity is 0 degC
    assert hot.inputs["u"].spec.present(32.0).to("degC").magnitude == pytest.approx(0.0,
                                                                                    abs=1e-9)


@pytest.mark.parametrize("units", [LABELS, ""], ids=["the SSD defines them", "only the FMUs"])
def test_an_ssd_connects_fmus_whose_units_both_define(tmp_path: Path, units: str) -> None:
    """The SSD's "[degF]" and "[K]" labels match the FMUs' own definitions of theirs, and the
    FMUs' labels when the SSD defines none."""
    hot, cold = gain_in(tmp_path, "[degF]", FAHRENHEIT), gain_in(tmp_path, "[K]",
                                                                  '<BaseUnit K="1"/>')
    system_text = """
<ssd:System name="Heat">
  <ssd:Elements>
    <ssd:Component name="Hot" source="hot.fmu">
      <ssd:Connectors>
        <ssd:Connector name="u" kind="input"><ssc:Real unit="[degF]"/></ssd:Connector>
        <ssd:Connector name="y" kind="output"><ssc:Real unit="[degF]"/></ssd:Connector>
      </ssd:Connectors>
      <ssd:ParameterBindings><ssd:ParameterBinding><ssd:ParameterValues>
        <ssv:ParameterSet version="1.0" name="start"><ssv:Parameters>
          <ssv:Parameter name="u"><ssv:Real value="373.15" unit="[K]"/></ssv:Parameter>
        </ssv:Parameters></ssv:ParameterSet>
      </ssd:ParameterValues></ssd:ParameterBinding></ssd:ParameterBindings>
    </ssd:Component>
    <ssd:Component name="Cold" source="cold.fmu">
      <ssd:Connectors>
        <ssd:Connector name="u" kind="input"><ssc:Real unit="[K]"/></ssd:Connector>
      </ssd:Connectors>
    </ssd:Component>
  </ssd:Elements>
  <ssd:Connections>
    <ssd:Connection startElement="Hot" startConnector="y" endElement="Cold" endConnector="u"/>
  </ssd:Connections>
</ssd:System>"""
    if not units:  # a value in a unit only the FMUs define: given in the FMU's own
        system_text = system_text.replace('value="373.15" unit="[K]"', 'value="212"')
    path = write_ssp(tmp_path / "heat.ssp", ssd(system_text, "heat", "", units))
    with zipfile.ZipFile(path, "a") as archive:
        archive.write(hot, "hot.fmu")
        archive.write(cold, "cold.fmu")
    system = read(path).system
    system.initialize(0.0)
    result = system.run(0.0, 0.5, 0.25)
    # 373.15 K is 212 [degF] at Hot.u, and back to 373.15 K at Cold.u
    assert result["Hot"][1]["y"][-1] == pytest.approx(212.0, abs=1e-9)
    assert result["Cold"][1]["y"][-1] == pytest.approx(373.15, abs=1e-9)
