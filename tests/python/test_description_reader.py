"""The lean modelDescription reader gives what fmpy's read_model_description gives, for the
fields syssimx reads, on our FMUs and on the Reference FMUs; units "-", "1" and "" are
dimensionless."""

from __future__ import annotations

import gc
import io
import logging
import os
import zipfile
from pathlib import Path

import pint
import pytest
from fixture_fmus import fmu_path
from fmpy import read_model_description
from syssimx import Connection, FMUComponent, System, fmus, units
from syssimx.errors import ConfigurationError, FMUFileError
from syssimx.fmu.description import read_description


def reference_fmus() -> list[Path]:
    root = Path(os.environ.get("SYSSIMX_REFERENCE_FMUS")
                or Path(__file__).resolve().parents[3] / "shared" / "reference-fmus")
    return sorted((root / "fmi2").glob("*.fmu"))


VARIABLE_FIELDS = ("name", "valueReference", "type", "causality", "variability", "initial",
                   "description", "unit", "start")
INTERFACE_FIELDS = ("modelIdentifier", "canGetAndSetFMUstate", "canSerializeFMUstate",
                    "canBeInstantiatedOnlyOncePerProcess", "providesDirectionalDerivative",
                    "canHandleVariableCommunicationStepSize", "needsExecutionTool")


def both(path: Path):
    with zipfile.ZipFile(path) as archive, archive.open("modelDescription.xml") as stream:
        ours = read_description(stream, path).description
    return ours, read_model_description(str(path), validate=False)


def assert_same(path: Path) -> None:
    ours, theirs = both(path)
    for name in ("fmiVersion", "modelName", "guid", "description", "generationTool"):
        assert getattr(ours, name) == getattr(theirs, name), name
    for name in INTERFACE_FIELDS:
        assert getattr(ours.coSimulation, name) == getattr(theirs.coSimulation, name), name
    for name in ("startTime", "stopTime", "stepSize", "tolerance"):
        assert getattr(ours.defaultExperiment, name) == getattr(theirs.defaultExperiment, name)
    assert len(ours.modelVariables) == len(theirs.modelVariables)
    for mine, fmpys in zip(ours.modelVariables, theirs.modelVariables, strict=True):
        for name in VARIABLE_FIELDS:
            assert getattr(mine, name) == getattr(fmpys, name), (mine.name, name)
        assert getattr(mine.declaredType, "name", None) == getattr(fmpys.declaredType, "name",
                                                                    None)
        assert getattr(mine.declaredType, "unit", None) == getattr(fmpys.declaredType, "unit",
                                                                    None)
    assert len(ours.outputs) == len(theirs.outputs)
    for mine, fmpys in zip(ours.outputs, theirs.outputs, strict=True):
        assert mine.variable.name == fmpys.variable.name
        assert (None if mine.dependencies is None else [v.name for v in mine.dependencies]) == \
            (None if fmpys.dependencies is None else [v.name for v in fmpys.dependencies])


# the FMI 2.0 builds; their FMI 3.0 twins (stem_fmi3) are read by FMPy, the FMI 1.0 ones
# (stem_fmi1, stem_fmi1_me) below
@pytest.mark.parametrize("name", [n for n in fmus.available()
                                  if not n.endswith(("_fmi3", "_fmi1", "_fmi1_me"))])
def test_our_fmus_read_as_fmpy_reads_them(name: str):
    assert_same(Path(fmus.path(name)))


@pytest.mark.parametrize("name", [n for n in fmus.available() if n.endswith(("_fmi1", "_fmi1_me"))])
def test_fmi1_builds_read_as_fmpy_reads_them(name: str):
    """FMI 1.0 in FMI 2.0's words, as FMPy reads it: parameters, internal variables as locals,
    no initial; the interface from Implementation; every output depending on every input."""
    ours, theirs = both(Path(fmus.path(name)))
    assert ours.fmiVersion == theirs.fmiVersion == "1.0"
    for name_ in ("modelName", "guid", "description", "numberOfContinuousStates",
                  "numberOfEventIndicators"):
        assert getattr(ours, name_) == getattr(theirs, name_), name_
    for part in ("coSimulation", "modelExchange"):
        mine, fmpys = getattr(ours, part), getattr(theirs, part)
        assert (mine is None) == (fmpys is None), part
        assert getattr(mine, "modelIdentifier", None) == getattr(fmpys, "modelIdentifier", None)
    assert len(ours.modelVariables) == len(theirs.modelVariables)
    for mine, fmpys in zip(ours.modelVariables, theirs.modelVariables, strict=True):
        for field in VARIABLE_FIELDS:
            assert getattr(mine, field) == getattr(fmpys, field), (mine.name, field)
    outputs = [v.name for v in ours.modelVariables if v.causality == "output"]
    assert [u.variable.name for u in ours.outputs] == outputs
    assert all(u.dependencies is None for u in ours.outputs)


def test_reference_fmus_read_as_fmpy_reads_them():
    paths = reference_fmus()
    if not paths:
        pytest.skip("the Reference FMUs are not there (set SYSSIMX_REFERENCE_FMUS)")
    for path in paths:
        assert_same(path)


# ------------------------------------------------------------------------------ units
@pytest.mark.parametrize("unit", ["-", "1", "", " - "])
def test_dimensionless_spellings(unit: str):
    assert units.to_unit(unit) == units.ureg.dimensionless


@pytest.mark.parametrize("unit", ["m/s/", "--", "bogus_unit"])
def test_units_pint_cannot_read_give_a_message(unit: str):
    with pytest.raises(ValueError, match=f"unit '{unit}' is unknown to pint") as caught:
        units.to_unit(unit)
    assert str(caught.value).endswith(")") and "()" not in str(caught.value)


def test_an_fmu_with_unit_dash_loads_and_runs(caplog: pytest.LogCaptureFixture):
    with caplog.at_level(logging.WARNING):
        dash = FMUComponent("D", fmu_path("unit_dash"))
    assert caplog.messages == []
    assert dash.output_specs["y"].unit == "-"
    dash.set_inputs({"u": 1.5})
    system = System("dash")
    system.add_component(dash)
    system.initialize(0.0)
    assert list(system.run(0.0, 0.1, 0.1)["D"][1]["y"]) == [3.0, 3.0]
    assert dash.get_outputs()["y"] == 3.0 * units.ureg.dimensionless


def test_a_dimensionless_port_connects_to_dimensionless_not_to_metres():
    system = System("dash")
    system.add_component(FMUComponent("A", fmu_path("unit_dash")))
    system.add_component(FMUComponent("B", fmu_path("unit_dash")))
    system.add_component(FMUComponent("G", fmus.path("gain")))
    system.add_connection(Connection("A", "y", "B", "u"))
    with pytest.raises(ConfigurationError, match="incompatible units '-' and 'm'"):
        system.add_connection(Connection("A", "y", "G", "u"))
    assert units.conversion("-", "1") == (1.0, 0.0)
    with pytest.raises(pint.DimensionalityError):
        units.conversion("-", "m")


def test_no_syssimx_error_has_an_empty_message():
    from syssimx.errors import FMUFileError, SimulationError, SysSimXError

    assert str(SysSimXError()) == "Base class of every syssimx error."
    assert str(FMUFileError("")) == ("The .fmu file cannot be used: missing, a broken or "
                                     "hostile archive, an invalid")
    assert str(SimulationError("", component="P")).startswith("A run failed.")


def test_what_tools_write_into_annotations_is_ignored_as_fmpy_ignores_it(tmp_path: Path):
    with zipfile.ZipFile(fmus.path("gain")) as gain:
        entries = {name: gain.read(name) for name in gain.namelist()}
    text = entries["modelDescription.xml"].decode()
    text = text.replace("  <ModelVariables>", """  <VendorAnnotations><Tool name="t">
    <CoSimulation modelIdentifier="elsewhere"/>
    <ScalarVariable name="ghost" valueReference="9"><Real/></ScalarVariable>
  </Tool></VendorAnnotations>
  <ModelVariables>""")
    text = text.replace('<Real start="1"/>', '<Real start="1"/><Annotations><Tool name="t">'
                        '<Real start="not a number"/><Unknown index="99"/></Tool></Annotations>')
    entries["modelDescription.xml"] = text.encode()
    path = tmp_path / "annotated.fmu"
    with zipfile.ZipFile(path, "w") as archive:
        for name, data in entries.items():
            archive.writestr(name, data)
    assert_same(path)
    ours, _ = both(path)
    assert [v.name for v in ours.modelVariables] == ["y", "u", "k"]
    assert ours.coSimulation.modelIdentifier == "gain"


# ------------------------------------------------------------------------------ XML forms
def gain_with_description(tmp_path: Path, text: str | bytes, name: str = "edited.fmu") -> Path:
    with zipfile.ZipFile(fmus.path("gain")) as gain:
        entries = {entry: gain.read(entry) for entry in gain.namelist()}
    entries["modelDescription.xml"] = text.encode() if isinstance(text, str) else text
    path = tmp_path / name
    with zipfile.ZipFile(path, "w") as archive:
        for entry, data in entries.items():
            archive.writestr(entry, data)
    return path


def gain_description() -> str:
    with zipfile.ZipFile(fmus.path("gain")) as gain:
        return gain.read("modelDescription.xml").decode()


def test_every_xml_form_reads_as_lxml_reads_it(tmp_path: Path):
    text = gain_description()
    text = text.replace("<fmiModelDescription", "<!-- generated -->\n<?tool x?>\n"
                        "<fmiModelDescription", 1)
    text = text.replace('description="output k * u"',
                        "description='a &lt;b&gt; &amp; &quot;c&quot; &apos;d&apos; &#233;&#x20AC;"
                        " tab\there line\nbreak CR LF\r\nend \u00e9'")
    text = text.replace('<Real unit="m" start="0"/>',
                        '<Real unit="m" start=" 2.5e-1 "/><![CDATA[ <Real start="9"/> ]]>'
                        '<!-- <Integer/> -->')
    path = gain_with_description(tmp_path, "\ufeff" + text)
    assert_same(path)
    ours, _ = both(path)
    assert ours.modelVariables[0].description == ("a <b> & \"c\" 'd' \u00e9\u20ac tab here line "
                                                  "break CR LF end \u00e9")
    assert ours.modelVariables[1].start == " 2.5e-1 "


def large_description(count: int) -> str:
    """A description of `count` variables of every type, causality and variability, with
    declared types, starts, units, descriptions and outputs with and without dependencies."""
    kinds = [
        ('causality="parameter" variability="fixed"',
         '<Real declaredType="Length" start="{i}.5"/>'),
        ('causality="parameter" variability="tunable"', '<Integer start="-{i}"/>'),
        ('causality="output"', '<Real unit="K"/>'),
        ('causality="input" variability="discrete"', '<Boolean start="true"/>'),
        ('causality="local" variability="constant"', '<String start="s{i}"/>'),
        ('', '<Enumeration declaredType="Mode" start="2"/>'),
        ('causality="calculatedParameter" variability="fixed"', '<Real/>'),
    ]
    variables = []
    outputs = []
    for i in range(count):
        head, value = kinds[i % len(kinds)]
        variables.append(f'<ScalarVariable name="v[{i}]" valueReference="{i}" {head} '
                         f'description="number {i}">{value.format(i=i)}</ScalarVariable>')
        if i % len(kinds) == 2:
            dependency = f' dependencies="{i - 1} {i + 2}"' if i % 3 else ""
            outputs.append(f'<Unknown index="{i + 1}"{dependency}/>')
    return f"""<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="large" guid="{{x}}">
  <CoSimulation modelIdentifier="gain"/>
  <DefaultExperiment startTime="0" stopTime="2"/>
  <TypeDefinitions>
    <SimpleType name="Length"><Real unit="m" quantity="Length"/></SimpleType>
    <SimpleType name="Mode" description="a mode"><Enumeration>
      <Item name="a" value="1"/><Item name="b" value="2"/></Enumeration></SimpleType>
  </TypeDefinitions>
  <ModelVariables>
    {chr(10).join(variables)}
  </ModelVariables>
  <ModelStructure><Outputs>{"".join(outputs)}</Outputs></ModelStructure>
</fmiModelDescription>
"""


def test_a_large_description_reads_as_fmpy_reads_it(tmp_path: Path):
    assert_same(gain_with_description(tmp_path, large_description(7000)))


def test_only_ports_become_objects_the_rest_is_looked_up_by_name(tmp_path: Path):
    from syssimx.fmu.info import read_fmu
    from syssimx.fmu.variable_table import ScalarVariable

    count = 20000
    path = gain_with_description(tmp_path, large_description(count))
    gc.collect()
    info = read_fmu(path)
    made = sum(isinstance(o, ScalarVariable) for o in gc.get_objects())
    ports = len(info.input_specs) + len(info.output_specs) + len(info.parameters)
    assert ports == sum(1 for i in range(count) if i % 7 < 4)  # parameters, outputs, inputs
    assert made <= ports + 1  # the declared types' variables are not among them
    assert len(info.variables) == count
    assert info.variables["v[19996]"].causality == "local"  # looked up, made on access
    assert info.variables["v[19996]"].start == "s19996"
    assert "v[20000]" not in info.variables
    with pytest.raises(KeyError):
        info.variables["v[20000]"]
    table = info.description.modelVariables
    assert [v.name for v in table[-2:]] == ["v[19998]", "v[19999]"]
    assert sum(1 for _ in table) == count
    assert info.parameters["v[1]"].start == -1
    assert info.parameters["v[0]"].unit == "m"
    assert info.feedthrough["v[2]"] == {"v[3]"} and info.feedthrough["v[23]"] == {"v[24]"}
    assert info.feedthrough["v[9]"] == set(info.input_specs)  # no dependencies: all of them


# ------------------------------------------------------------------------------ refusals
MINIMAL = """<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g">
  <TypeDefinitions>
    <SimpleType name="T"><Real/></SimpleType>
  </TypeDefinitions>
  <ModelVariables>
    <ScalarVariable name="x" valueReference="0" causality="output"><Real start="1"/>
    </ScalarVariable>
  </ModelVariables>
  <ModelStructure><Outputs><Unknown index="1" dependencies="1"/></Outputs></ModelStructure>
</fmiModelDescription>
"""


def read_text(text: str | bytes):
    data = text.encode() if isinstance(text, str) else text
    return read_description(io.BytesIO(data), "m.fmu").description


@pytest.mark.parametrize(("old", "new", "message"), [
    ('<Real start="1"/>', '<Real start="0x1p3"/>', "variable 'x': start '0x1p3' is not a Real "
                                                    "value"),
    ('<Real start="1"/>', '<Integer start="2147483648"/>',
     "variable 'x': start '2147483648' is not a Integer value"),
    ('<Real start="1"/>', '<Boolean start="yes"/>', "variable 'x': start 'yes' is not a Boolean "
                                                     "value"),
    ('causality="output"', 'causality="output" initial="sometimes"',
     "variable 'x': initial='sometimes' is not one of exact, approx, calculated"),
    ('causality="output"', 'causality="outlet"',
     "variable 'x': causality='outlet' with variability='continuous' is not allowed"),
    ('name="x" ', "", "a ScalarVariable has no name (valueReference '0')"),
    ('<SimpleType name="T"><Real/></SimpleType>', '<SimpleType name="T"></SimpleType>',
     "SimpleType 'T' has no type element"),
    ('dependencies="1"', 'dependencies="1 2"', "ModelStructure index '2' names no variable "
                                               "(there are 1)"),
    ('dependencies="1"', 'dependencies="1 &amp;x"', "ModelStructure index '&x' names no "
                                                    "variable (there are 1)"),
    ('<Unknown index="1"', '<Unknown', "ModelStructure index None names no variable (there are "
                                      "1)"),
    ("</ModelVariables>", "</ModelVariable>", "not well-formed XML: line 9: end tag "
                                              "</ModelVariable> does not match <ModelVariables> "
                                              "of line 6"),
    ('encoding="UTF-8"', 'encoding="x-unknown"', "its XML declaration names the encoding "
                                                 "'x-unknown', which Python does not know"),
    ('<fmiModelDescription', '<!DOCTYPE m [<!ENTITY a "aaaaaaaaaa">]>\n<fmiModelDescription',
     "not well-formed XML: line 2: a DOCTYPE is not accepted in a modelDescription"),
    ('modelName="m"', 'modelName="&a;"', "not well-formed XML: line 2: '&a...' is neither a "
                                         "predefined entity"),
    ('modelName="m"', 'modelName="\x01"', "not well-formed XML: line 2: character U+0001 is not "
                                          "allowed in XML"),
])
def test_what_is_refused_is_named(old: str, new: str, message: str):
    assert old in MINIMAL
    with pytest.raises(FMUFileError) as caught:
        read_text(MINIMAL.replace(old, new, 1))
    assert str(caught.value).startswith(f"m.fmu: modelDescription.xml: {message}")


def test_bytes_that_are_not_utf8_are_refused():
    with pytest.raises(FMUFileError, match=r"m.fmu: modelDescription.xml: not well-formed XML: "
                                           r"line 2: invalid UTF-8 \(a sequence starting with "
                                           r"byte 0xE9\)"):
        read_text(MINIMAL.encode().replace(b'modelName="m"', b'modelName="\xe9"'))


def test_a_declared_encoding_is_read():
    text = MINIMAL.replace('encoding="UTF-8"', 'encoding="ISO-8859-1"').replace(
        'modelName="m"', 'modelName="Gefäß"')
    assert read_text(text.encode("latin-1")).modelName == "Gefäß"


@pytest.mark.parametrize("start", ["INF", "-inf", "NaN", " 1e5 ", ".5", "5.", "+1E-3"])
def test_real_starts_python_reads_are_accepted(start: str):
    description = read_text(MINIMAL.replace('start="1"', f'start="{start}"'))
    assert description.modelVariables[0].start == start
    float(start)


FMI1 = """<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="1.0" modelName="m" modelIdentifier="m_id" guid="{g}"
    numberOfContinuousStates="2" numberOfEventIndicators="1">
  <ModelVariables>
    <ScalarVariable name="u" valueReference="0" causality="input"><Real start="1"/>
    </ScalarVariable>
    <ScalarVariable name="k" valueReference="1" variability="parameter"><Real start="2"/>
    </ScalarVariable>
    <ScalarVariable name="y" valueReference="2" causality="output"><Real/></ScalarVariable>
    <ScalarVariable name="minus_y" valueReference="2" causality="output" alias="negatedAlias">
      <Real/></ScalarVariable>
  </ModelVariables>
</fmiModelDescription>
"""


def test_fmi1_without_implementation_is_model_exchange():
    description = read_text(FMI1)
    assert description.fmiVersion == "1.0"
    assert description.coSimulation is None
    assert description.modelExchange.modelIdentifier == "m_id"
    assert not description.modelExchange.canGetAndSetFMUstate
    assert (description.numberOfContinuousStates, description.numberOfEventIndicators) == (2, 1)
    causalities = {v.name: (v.causality, v.variability) for v in description.modelVariables}
    assert causalities == {"u": ("input", "continuous"), "k": ("parameter", "fixed"),
                           "y": ("output", "continuous"),
                           "minus_y": ("local", "continuous")}  # a negated alias is no port
    assert [u.variable.name for u in description.outputs] == ["y"]


def test_fmi1_with_implementation_is_co_simulation():
    text = FMI1.replace("</fmiModelDescription>", """  <Implementation><CoSimulation_Tool>
    <Capabilities canHandleVariableCommunicationStepSize="true"/>
    <Model entryPoint="fmu://tool" type="application/x-tool"/>
  </CoSimulation_Tool></Implementation>
</fmiModelDescription>""")
    description = read_text(text)
    assert description.modelExchange is None
    assert description.coSimulation.modelIdentifier == "m_id"
    assert description.coSimulation.canHandleVariableCommunicationStepSize


def test_other_fmi_versions_are_refused_naming_what_runs():
    with pytest.raises(FMUFileError, match=r"^m\.fmu: FMI version 4\.0 is not supported "
                       r"\(syssimx runs FMI 1\.0, FMI 2\.0 and FMI 3\.0 Co-Simulation and "
                       r"Model Exchange FMUs\)$"):
        read_text(MINIMAL.replace('fmiVersion="2.0"', 'fmiVersion="4.0"'))
