"""SSP constructs OMSimulator and libcosim write, each in an SSD written here from the standard:
SSP 2.0 files read as their SSP 1.0 constructs, values bound to system connectors, bindings
that set inputs' starts, one-to-many parameter mappings, names that name nothing (lenient and
strict), XML Schema booleans, units of parameter values, the implementation attribute,
connector cycles and connections to unknown elements. Numbers are closed forms: the gain FMU
computes y = k u, the sliding mass without friction x = x0 + v0 t."""

from __future__ import annotations

import re
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from ssp_archive import reference_fmu, ssd, write_ssp
from syssimx import System
from syssimx.cli import main
from syssimx.ssp import SSPError, SSPWarning, load, read


def values(names: dict[str, str]) -> str:
    """An inline parameter binding: {name: '<ssv:Real value="..."/>'}."""
    parameters = "".join(f'<ssv:Parameter name="{n}">{v}</ssv:Parameter>'
                         for n, v in names.items())
    return ('<ssd:ParameterBindings><ssd:ParameterBinding><ssd:ParameterValues>'
            f'<ssv:ParameterSet version="1.0" name="values"><ssv:Parameters>{parameters}'
            '</ssv:Parameters></ssv:ParameterSet></ssd:ParameterValues></ssd:ParameterBinding>'
            '</ssd:ParameterBindings>')


def real(value: float, unit: str = "") -> str:
    return f'<ssv:Real value="{value}"{f" unit={unit!r}" if unit else ""}/>'.replace("'", '"')


def loaded(tmp_path: Path, system: str, bundled: tuple[str, ...] = ("gain",),
           units: str = "", strict: bool = False,
           version: str = "1.0") -> tuple[System, list[str], Path]:
    """The system of the SSD around `system`, and the SSPWarnings it gave."""
    text = ssd(system, "t", units=units).replace('version="1.0" name="t"',
                                                 f'version="{version}" name="t"')
    path = write_ssp(tmp_path / "t.ssp", text, bundled=bundled)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        imported = read(path, strict=strict)
    return imported.system, [str(w.message) for w in caught if w.category is SSPWarning], path


def run_and_read(system: System, component: str, variable: str, tf: float = 0.3) -> Any:
    system.initialize(0.0)
    system.run(0.0, tf, 0.1)
    return system.components[component].get_state()[variable]["value"]


# ------------------------------------------------------------------ values on system connectors
NESTED = """
<ssd:System name="Top">
  <ssd:Connectors>
    <ssd:Connector name="gain" kind="parameter"><ssc:Real/></ssd:Connector>
    <ssd:Connector name="level" kind="input"><ssc:Real/></ssd:Connector>
  </ssd:Connectors>
  {top_values}
  <ssd:Elements>
    <ssd:System name="Inner">
      <ssd:Connectors>
        <ssd:Connector name="k" kind="parameter"><ssc:Real/></ssd:Connector>
        <ssd:Connector name="u" kind="input"><ssc:Real/></ssd:Connector>
      </ssd:Connectors>
      {inner_values}
      <ssd:Elements>
        <ssd:Component name="Gain" source="resources/gain.fmu">{gain_values}</ssd:Component>
      </ssd:Elements>
      <ssd:Connections>
        <ssd:Connection startConnector="k" endElement="Gain" endConnector="k"/>
        <ssd:Connection startConnector="u" endElement="Gain" endConnector="u">
          <ssc:LinearTransformation factor="2" offset="1"/>
        </ssd:Connection>
      </ssd:Connections>
    </ssd:System>
  </ssd:Elements>
  <ssd:Connections>
    <ssd:Connection startConnector="gain" endElement="Inner" endConnector="k"/>
    <ssd:Connection startConnector="level" endElement="Inner" endConnector="u"/>
  </ssd:Connections>
</ssd:System>"""


def nested(top: dict[str, str], inner: dict[str, str], gain: dict[str, str]) -> str:
    return NESTED.format(top_values=values(top) if top else "",
                         inner_values=values(inner) if inner else "",
                         gain_values=values(gain) if gain else "")


def test_values_on_the_root_systems_connectors_drive_a_nested_component(tmp_path: Path) -> None:
    """Top.gain = 2.5 drives Inner.k, which drives Gain.k (over Inner's own 7 and Gain's own
    1: a connection wins over a value bound to its end, as OMSimulator does); Top.level = 4
    drives Gain.u's start through the transformation: u = 2 * 4 + 1 = 9, y = 2.5 * 9."""
    system, caught, _ = loaded(tmp_path, nested({"gain": real(2.5), "level": real(4)},
                                                {"k": real(7)}, {"k": real(1)}))
    assert caught == []
    gain = system.components["Inner.Gain"]
    assert gain.user_parameters() == {"k": 2.5}
    assert gain.input_start("u") == 9.0
    assert run_and_read(system, "Inner.Gain", "y") == 22.5


def test_a_value_on_an_inner_connector_applies_when_nothing_outer_gives_one(
        tmp_path: Path) -> None:
    system, caught, _ = loaded(tmp_path, nested({"level": real(4)}, {"k": real(7)}, {}))
    assert caught == []
    assert system.components["Inner.Gain"].user_parameters() == {"k": 7.0}
    assert run_and_read(system, "Inner.Gain", "y") == 63.0


def test_a_system_connector_without_value_warns_and_keeps_the_start(tmp_path: Path) -> None:
    system, caught, path = loaded(tmp_path, nested({}, {}, {}))
    assert len(caught) == 1
    assert caught[0].startswith("a connection from a system connector that has no value and "
                                f"nothing drives is not supported and is ignored: {path}:")
    assert run_and_read(system, "Inner.Gain", "y") == 0.0  # k = 1 and u = 0: the FMU's starts


# ------------------------------------------------------------------ bindings set inputs' starts
def test_a_binding_sets_an_inputs_start(tmp_path: Path) -> None:
    """OMSimulator's LinearTransformation3 binds Gain1.u = 14."""
    system, caught, _ = loaded(tmp_path, '<ssd:System name="s"><ssd:Elements><ssd:Component '
                               f'name="Gain" source="resources/gain.fmu">'
                               f'{values({"u": real(14), "k": real(0.5)})}</ssd:Component>'
                               '</ssd:Elements></ssd:System>')
    assert caught == []
    assert system.components["Gain"].input_start("u") == 14.0
    assert run_and_read(system, "Gain", "y") == 7.0


# ------------------------------------------------------------------ one source, several targets
def test_every_mapping_entry_of_one_source_applies(tmp_path: Path) -> None:
    """OMSimulator's embrace system maps one value to several parameters; each target gets it
    (A.k = 3, B.k = 2 * 3 - 1 by its own transformation)."""
    binding = values({"shared": real(3)}).replace(
        "</ssd:ParameterValues>",
        '</ssd:ParameterValues><ssd:ParameterMapping><ssm:ParameterMapping version="1.0">'
        '<ssm:MappingEntry source="shared" target="A.k"/>'
        '<ssm:MappingEntry source="shared" target="B.k">'
        '<ssc:LinearTransformation factor="2" offset="-1"/></ssm:MappingEntry>'
        '</ssm:ParameterMapping></ssd:ParameterMapping>')
    system, caught, _ = loaded(
        tmp_path, f'<ssd:System name="s">{binding}<ssd:Elements>'
        '<ssd:Component name="A" source="resources/gain.fmu"/>'
        '<ssd:Component name="B" source="resources/gain.fmu"/></ssd:Elements></ssd:System>')
    assert caught == []
    assert system.components["A"].user_parameters() == {"k": 3.0}
    assert system.components["B"].user_parameters() == {"k": 5.0}


# ------------------------------------------------------------------ names that name nothing
GHOSTS = ('<ssd:System name="s">' + values({"Ghost.k": real(1), "Gain.nothing": real(2),
                                            "Gain.k": real(3)})
          + '<ssd:Elements><ssd:Component name="Gain" source="resources/gain.fmu"/>'
            '</ssd:Elements></ssd:System>')


def test_values_that_name_nothing_warn_once_each_naming_file_and_parameter(
        tmp_path: Path) -> None:
    system, caught, path = loaded(tmp_path, GHOSTS)
    where = f"{path}:SystemStructure.ssd: <ParameterBinding> (line 3): <Parameter '{{}}'> " \
            "(line 3)"
    assert caught == [
        f"{where.format('Ghost.k')}: parameter 'Ghost.k' names no component or connector of "
        "the root system; the value is ignored",
        f"{where.format('Gain.nothing')}: component 'Gain' has no parameter or input "
        "'nothing'; the value is ignored"]
    assert system.components["Gain"].user_parameters() == {"k": 3.0}  # the rest is read


def test_strict_refuses_a_value_that_names_nothing(tmp_path: Path) -> None:
    with pytest.raises(SSPError, match=re.escape("<Parameter 'Ghost.k'> (line 3): parameter "
                                                 "'Ghost.k' names no component or connector "
                                                 "of the root system (strict)")):
        loaded(tmp_path, GHOSTS, strict=True)


def test_the_command_lines_strict_option_refuses_in_one_line(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = write_ssp(tmp_path / "t.ssp", ssd(GHOSTS, "t", '<ssd:DefaultExperiment '
                                                          'stopTime="0.2"/>'), bundled=("gain",))
    assert main(["run", str(path), "--strict", "--dt", "0.1", "--quiet"]) == 1
    err = capsys.readouterr().err
    assert err.startswith(f"syssimx: error: {path}:SystemStructure.ssd: <ParameterBinding> "
                          "(line 3): <Parameter 'Ghost.k'>")
    assert err.count("\n") == 1
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert main(["run", str(path), "--dt", "0.1", "--quiet"]) == 0


# ------------------------------------------------------------------ XML Schema booleans
@pytest.mark.parametrize(("text", "expected"), [("1", True), ("0", False), ("true", True),
                                                ("false", False)])
def test_boolean_values_are_xml_schema_booleans(tmp_path: Path, text: str,
                                                expected: bool) -> None:
    """The Reference Feedthrough FMU: Boolean_output = Boolean_input."""
    import zipfile

    fmu = reference_fmu("Feedthrough")
    system_text = ('<ssd:System name="s"><ssd:Elements><ssd:Component name="F" '
                   'source="Feedthrough.fmu">'
                   + values({"Boolean_input": f'<ssv:Boolean value="{text}"/>'})
                   + '</ssd:Component></ssd:Elements></ssd:System>')
    path = write_ssp(tmp_path / "b.ssp", ssd(system_text))
    with zipfile.ZipFile(path, "a") as archive:
        archive.write(fmu, "Feedthrough.fmu")
    system = load(path)
    assert run_and_read(system, "F", "Boolean_output") is expected


# ------------------------------------------------------------------ units of parameter values
MASS = ('<ssd:System name="s"><ssd:Elements><ssd:Component name="Mass" '
        'source="resources/sliding_mass.fmu">{binding}</ssd:Component></ssd:Elements>'
        '</ssd:System>')
UNITS = """<ssd:Units>
  <ssc:Unit name="six_feet"><ssc:BaseUnit m="1" factor="1.8288"/></ssc:Unit>
  <ssc:Unit name="Ohm"><ssc:BaseUnit kg="1" m="2" s="-3" A="-2"/></ssc:Unit>
</ssd:Units>"""


def x0_of(tmp_path: Path, binding: str, units: str = UNITS) -> float:
    system, caught, _ = loaded(tmp_path, MASS.format(binding=binding), ("sliding_mass",),
                               units)
    assert caught == []
    return system.components["Mass"].user_parameters()["x0"]


def test_a_unit_the_ssd_defines_converts_a_parameter_value(tmp_path: Path) -> None:
    """x0 = 2 six_feet, defined in the SSD's ssc:Units as 1.8288 m: 3.6576 m."""
    assert x0_of(tmp_path, values({"x0": real(2, "six_feet")})) == pytest.approx(3.6576,
                                                                                 rel=1e-15)


def test_a_unit_the_parameter_set_defines_converts_its_values(tmp_path: Path) -> None:
    binding = values({"x0": real(2, "half_metre")}).replace(
        "</ssv:Parameters>", '</ssv:Parameters><ssv:Units><ssc:Unit name="half_metre">'
                             '<ssc:BaseUnit m="1" factor="0.5"/></ssc:Unit></ssv:Units>')
    assert x0_of(tmp_path, binding) == 1.0


def test_a_unit_pint_knows_converts_without_a_definition(tmp_path: Path) -> None:
    assert x0_of(tmp_path, values({"x0": real(50, "cm")})) == 0.5


@pytest.mark.parametrize(("unit", "problem"), [
    ("Ohm", "is not convertible to m"),  # defined in the SSD, a resistance
    ("bogus", "unit 'bogus' is unknown to pint"),
    ("s", "is not convertible to m"),
])
def test_a_unit_that_does_not_fit_is_an_ssp_error_naming_the_parameter(
        tmp_path: Path, unit: str, problem: str) -> None:
    with pytest.raises(SSPError, match=r"t\.ssp:SystemStructure\.ssd: <ParameterBinding> \(line "
                                      r"3\): <Parameter 'x0'> \(line 3\): "
                                      rf".*{re.escape(problem)}"):
        x0_of(tmp_path, values({"x0": real(2, unit)}))


def test_units_both_defined_in_the_ssd_convert_by_their_definitions(tmp_path: Path) -> None:
    """An FMU unit the SSD defines too ("m" here) converts without pint; a different quantity
    is refused by the definitions' exponents."""
    units = UNITS.replace("</ssd:Units>", '<ssc:Unit name="m"><ssc:BaseUnit m="1"/>'
                                          '</ssc:Unit></ssd:Units>')
    assert x0_of(tmp_path, values({"x0": real(2, "six_feet")}), units) == \
        pytest.approx(3.6576, rel=1e-15)
    with pytest.raises(SSPError, match="unit 'Ohm' and the FMU's unit 'm' measure different "
                                       "quantities"):
        x0_of(tmp_path, values({"x0": real(2, "Ohm")}), units)


# ------------------------------------------------------------------ implementation
@pytest.mark.parametrize(("implementation", "interface"), [
    ("ModelExchange", "model-exchange"), ("CoSimulation", "co-simulation"),
    ("any", "co-simulation")])  # any: the FMU's first interface, Co-Simulation
def test_the_implementation_attribute_chooses_the_interface(
        tmp_path: Path, implementation: str, interface: str) -> None:
    binding = values({"mu": real(0), "x0": real(0.5), "v0": real(2)})
    text = MASS.format(binding=binding).replace(
        'name="Mass"', f'name="Mass" implementation="{implementation}"')
    system, caught, _ = loaded(tmp_path, text, ("sliding_mass",))
    assert caught == []
    assert system.components["Mass"].fmu_interface.name == interface
    system.initialize(0.0)
    t, outputs = system.run(0.0, 1.0, 0.1)["Mass"]
    np.testing.assert_allclose(outputs["x"], 0.5 + 2.0 * t, rtol=0, atol=1e-9)


# ------------------------------------------------------------------ SSP 2.0
VERSION_2 = ('<ssd:System name="s"><ssd:Elements><ssd:Component name="Gain" '
             'source="resources/gain.fmu" newAttribute="x"><ssd:Connectors>'
             '<ssd:Connector name="u" kind="input"><ssc:Float64/></ssd:Connector>'
             '</ssd:Connectors></ssd:Component></ssd:Elements></ssd:System>')


def test_an_ssp_2_file_is_read_as_its_ssp_1_constructs(tmp_path: Path) -> None:
    """Elements and attributes the SSP 1.0 schemas do not declare: one warning each."""
    system, caught, path = loaded(tmp_path, VERSION_2, version="2.0")
    where = f"{path}:SystemStructure.ssd"
    assert caught == [
        f"SSP 2.0 attribute 'newAttribute' is not supported and is ignored: {where}: "
        "<Component 'Gain'> (line 3), read as SSP 1.0",
        f"SSP 2.0 element <Float64> is not supported and is ignored: {where}: <Float64> "
        "(line 3), read as SSP 1.0"]
    assert list(system.components) == ["Gain"]


def test_strict_refuses_what_ssp_1_does_not_have(tmp_path: Path) -> None:
    with pytest.raises(SSPError, match=r"SSP 2\.0 attribute 'newAttribute' is not supported "
                                       r"\(strict\)"):
        loaded(tmp_path, VERSION_2, version="2.0", strict=True)


def test_an_ssp_2_file_must_satisfy_the_ssp_1_schema_otherwise(tmp_path: Path) -> None:
    misplaced = VERSION_2.replace('<ssd:Elements>', '<ssd:Elements><ssd:Connectors/>')
    with pytest.raises(SSPError, match=r"not a valid SSD file \(version 2\.0 read as its SSP "
                                       r"1\.0 constructs, against the SSP 1\.0 schema\): "
                                       r"line 3: Element .*Connectors"):
        loaded(tmp_path, misplaced, version="2.0")


# ------------------------------------------------------------------ connections
CYCLE = """<ssd:System name="s">
  <ssd:Connectors>
    <ssd:Connector name="x" kind="input"><ssc:Real/></ssd:Connector>
    <ssd:Connector name="y" kind="input"><ssc:Real/></ssd:Connector>
  </ssd:Connectors>
  <ssd:Elements><ssd:Component name="Gain" source="resources/gain.fmu"/></ssd:Elements>
  <ssd:Connections>
    <ssd:Connection startConnector="y" endConnector="x"/>
    <ssd:Connection startConnector="x" endConnector="y"/>
    <ssd:Connection startConnector="x" endElement="Gain" endConnector="u"/>
  </ssd:Connections>
</ssd:System>"""


def test_system_connectors_in_a_cycle_are_an_error_naming_them(tmp_path: Path) -> None:
    """It looped forever before (issue 20, item 8)."""
    with pytest.raises(SSPError, match=r"<Connection> \(line \d+\): the system connectors "
                                       r"(x -> y -> x|y -> x -> y) form a cycle"):
        loaded(tmp_path, CYCLE)


def test_a_cycle_that_drives_no_component_is_an_error_too(tmp_path: Path) -> None:
    alone = CYCLE.replace('<ssd:Connection startConnector="x" endElement="Gain" '
                          'endConnector="u"/>', "")
    with pytest.raises(SSPError, match=r"the system connectors (x -> y -> x|y -> x -> y) "
                                       r"form a cycle"):
        loaded(tmp_path, alone)


UNKNOWN_END = ('<ssd:System name="s"><ssd:Elements><ssd:Component name="Gain" '
               'source="resources/gain.fmu"/></ssd:Elements><ssd:Connections>'
               '<ssd:Connection startElement="Gain" startConnector="y" endElement="Nobody" '
               'endConnector="u"/></ssd:Connections></ssd:System>')


def test_a_connection_to_an_unknown_element_warns_naming_it(tmp_path: Path) -> None:
    """It was dropped silently before (issue 20, item 9)."""
    system, caught, path = loaded(tmp_path, UNKNOWN_END)
    assert caught == [f"{path}:SystemStructure.ssd: <Connection> (line 3): endElement "
                      "'Nobody' names no element of the root system; the connection is left "
                      "out"]
    assert system.connections == []


def test_strict_refuses_a_connection_to_an_unknown_element(tmp_path: Path) -> None:
    with pytest.raises(SSPError, match=r"endElement 'Nobody' names no element of the root "
                                       r"system \(strict\)"):
        loaded(tmp_path, UNKNOWN_END, strict=True)


def test_a_connection_to_an_undeclared_system_connector_warns_naming_it(tmp_path: Path) -> None:
    text = UNKNOWN_END.replace('endElement="Nobody" ', "")
    _, caught, _ = loaded(tmp_path, text)
    assert len(caught) == 1
    assert caught[0].endswith("endConnector 'u' names no connector of the root system; the "
                              "connection is left out")


def test_a_connection_to_a_component_left_out_says_so(tmp_path: Path) -> None:
    text = UNKNOWN_END.replace(
        "</ssd:Elements>", '<ssd:Component name="Nobody" type="application/x-ssp-package" '
                           'source="resources/gain.fmu"/></ssd:Elements>')
    _, caught, _ = loaded(tmp_path, text)
    assert [m.split(": ")[-1] for m in caught] == [
        "<Component 'Nobody'> (line 3)",
        "endElement 'Nobody' is a component syssimx leaves out; the connection is left out"]


def test_a_parameter_set_of_version_2_is_read_as_its_ssp_1_constructs(tmp_path: Path) -> None:
    ssv = ('<ssv:ParameterSet xmlns:ssv="http://ssp-standard.org/SSP1/'
           'SystemStructureParameterValues" version="2.0" name="p"><ssv:Parameters>'
           '<ssv:Parameter name="k"><ssv:Float64 value="1"/><ssv:Real value="4"/>'
           '</ssv:Parameter></ssv:Parameters></ssv:ParameterSet>')
    text = ('<ssd:System name="s"><ssd:Elements><ssd:Component name="Gain" '
            'source="resources/gain.fmu"><ssd:ParameterBindings><ssd:ParameterBinding '
            'source="p.ssv"/></ssd:ParameterBindings></ssd:Component></ssd:Elements>'
            '</ssd:System>')
    path = write_ssp(tmp_path / "t.ssp", ssd(text), {"p.ssv": ssv}, ("gain",))
    with pytest.warns(SSPWarning) as caught:
        system = load(path)
    assert [str(w.message) for w in caught] == [
        f"SSP 2.0 element <Float64> is not supported and is ignored: {path}:p.ssv: <Float64> "
        "(line 1), read as SSP 1.0"]
    assert system.components["Gain"].user_parameters() == {"k": 4.0}
