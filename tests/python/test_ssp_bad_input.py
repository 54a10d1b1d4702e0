"""Bad SSP input: each an SSPError naming the file and the element; nothing extracted outside
the temporary folder. Unsupported elements: one SSPWarning each, naming it."""

from __future__ import annotations

import re
import shutil
import stat
import tempfile
import warnings
import zipfile
from pathlib import Path

import pytest
from ssp_archive import ssd, write_ssp
from syssimx import fmus
from syssimx.ssp import SSPError, SSPWarning, load

MASS = """<ssd:Component name="Mass" source="resources/sliding_mass.fmu">
  <ssd:Connectors>{connectors}</ssd:Connectors>
</ssd:Component>"""
X_OUTPUT = '<ssd:Connector name="x" kind="output"><ssc:Real unit="m"/></ssd:Connector>'


def one_mass(tmp_path: Path, connectors: str = X_OUTPUT, extra_elements: str = "",
             connections: str = "", experiment: str = "") -> Path:
    system = (f'<ssd:System name="s"><ssd:Elements>{MASS.format(connectors=connectors)}'
              f'{extra_elements}</ssd:Elements>{connections}</ssd:System>')
    return write_ssp(tmp_path / "s.ssp", ssd(system, "s", experiment), bundled=("sliding_mass",))


def leftover_folders() -> set[str]:
    return {p.name for p in Path(tempfile.gettempdir()).glob("syssimx-ssp-*")}


def test_a_missing_fmu_names_the_file_and_the_component(tmp_path: Path) -> None:
    system = ('<ssd:System name="s"><ssd:Elements><ssd:Component name="Ghost" '
              'source="resources/ghost.fmu"/></ssd:Elements></ssd:System>')
    path = write_ssp(tmp_path / "s.ssp", ssd(system))
    before = leftover_folders()
    with pytest.raises(SSPError, match=rf"{path}:SystemStructure\.ssd: <Component 'Ghost'> "
                                      r"\(line 3\): "
                                      r"source 'resources/ghost.fmu' not found in the archive"):
        load(path)
    assert leftover_folders() == before  # the extraction folder is removed


def test_a_connector_the_fmu_does_not_have(tmp_path: Path) -> None:
    connector = '<ssd:Connector name="y" kind="output"><ssc:Real/></ssd:Connector>'
    with pytest.raises(SSPError, match=r"<Connector 'y'> \(line \d+\): 'Mass' \(.*sliding_mass"
                                      r"\.fmu\) has no output 'y'"):
        load(one_mass(tmp_path, connector))


def test_a_connector_type_that_does_not_match_the_fmu(tmp_path: Path) -> None:
    connector = '<ssd:Connector name="x" kind="output"><ssc:Integer/></ssd:Connector>'
    with pytest.raises(SSPError, match=r"s\.ssp:SystemStructure\.ssd: <Connector 'x'> \(line "
                                      r"\d+\): type Integer does not match the FMU's REAL "
                                      r"variable 'x' of 'Mass'"):
        load(one_mass(tmp_path, connector))


def test_a_connector_unit_that_does_not_match_the_fmu(tmp_path: Path) -> None:
    connector = '<ssd:Connector name="x" kind="output"><ssc:Real unit="s"/></ssd:Connector>'
    with pytest.raises(SSPError, match=r"<Connector 'x'> \(line \d+\): unit 's' does not match "
                                      r"the FMU's unit 'm' of Mass.x"):
        load(one_mass(tmp_path, connector))


def test_a_connection_between_units_of_different_quantities(tmp_path: Path) -> None:
    sliding = ('<ssd:Component name="Ball" source="resources/bouncing_ball_euler.fmu"/>')
    connections = ('<ssd:Connections><ssd:Connection startElement="Ball" startConnector="v" '
                   'endElement="Gain" endConnector="u"/></ssd:Connections>')
    system = (f'<ssd:System name="s"><ssd:Elements>{sliding}<ssd:Component name="Gain" '
              f'source="resources/gain.fmu"/></ssd:Elements>{connections}</ssd:System>')
    path = write_ssp(tmp_path / "s.ssp", ssd(system), bundled=("bouncing_ball_euler", "gain"))
    with pytest.raises(SSPError, match=r"<Connection> \(line \d+\): Ball.v -> Gain.u: "
                                      r"incompatible units 'm/s' and 'm'"):
        load(path)


def test_malformed_xml_names_the_file_and_the_line(tmp_path: Path) -> None:
    path = write_ssp(tmp_path / "s.ssp", ssd('<ssd:System name="s">'), bundled=())
    with pytest.raises(SSPError, match=r"SystemStructure\.ssd: malformed XML: .*line"):
        load(path)


def test_an_ssd_against_the_schema_names_the_element(tmp_path: Path) -> None:
    path = write_ssp(tmp_path / "s.ssp", ssd('<ssd:System name="s"><ssd:Bogus/></ssd:System>'))
    with pytest.raises(SSPError, match=r"SystemStructure\.ssd: not a valid SSD file \(SSP 1.0 "
                                      r"schema\): line \d+: Element .*Bogus"):
        load(path)


def test_a_parameter_for_no_parameter_names_the_ssv_and_the_element(tmp_path: Path) -> None:
    """OMSimulator ignores such a value: one warning naming it (an error under strict)."""
    ssv = ('<ssv:ParameterSet xmlns:ssv="http://ssp-standard.org/SSP1/'
           'SystemStructureParameterValues" version="1.0" name="p"><ssv:Parameters>'
           '<ssv:Parameter name="Mass.nothing"><ssv:Real value="1"/></ssv:Parameter>'
           '</ssv:Parameters></ssv:ParameterSet>')
    system = (f'<ssd:System name="s"><ssd:ParameterBindings><ssd:ParameterBinding '
              f'source="p.ssv"/></ssd:ParameterBindings><ssd:Elements>'
              f'{MASS.format(connectors=X_OUTPUT)}</ssd:Elements></ssd:System>')
    path = write_ssp(tmp_path / "s.ssp", ssd(system), {"p.ssv": ssv}, ("sliding_mass",))
    problem = (f"{path}:p.ssv: <Parameter 'Mass.nothing'> (line 1): component 'Mass' has no "
               "parameter or input 'nothing'")
    with pytest.warns(SSPWarning) as caught:
        load(path)
    assert [str(w.message) for w in caught] == [f"{problem}; the value is ignored"]
    with pytest.raises(SSPError, match=re.escape(f"{problem} (strict)")):
        load(path, strict=True)


@pytest.mark.parametrize(("entry", "problem"), [
    ("../escaped.txt", "climbs out of the archive with '..'"),
    ("/tmp/absolute.txt", "has an absolute path"),
    ("link", "is a symbolic link"),
])
def test_archive_entries_that_escape_are_refused(tmp_path: Path, entry: str,
                                                 problem: str) -> None:
    path = write_ssp(tmp_path / "s.ssp", ssd('<ssd:System name="s"/>'))
    with zipfile.ZipFile(path, "a") as archive:
        info = zipfile.ZipInfo(entry)
        if entry == "link":
            info.external_attr = (stat.S_IFLNK | 0o777) << 16
        archive.writestr(info, "/etc/passwd" if entry == "link" else "outside")
    before = leftover_folders()
    with pytest.raises(SSPError, match=re.escape(f"{path}: archive entry {entry!r} {problem}")):
        load(path)
    assert leftover_folders() == before
    assert not (tmp_path / "escaped.txt").exists()


def test_a_file_that_is_not_a_zip(tmp_path: Path) -> None:
    path = tmp_path / "s.ssp"
    path.write_text("not a zip")
    with pytest.raises(SSPError, match=re.escape(f"{path} is not an SSP: the file is not a "
                                                 "readable zip archive")):
        load(path)


def test_an_archive_without_a_system_structure(tmp_path: Path) -> None:
    path = tmp_path / "s.ssp"
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("other.xml", "<a/>")
    with pytest.raises(SSPError, match=re.escape(f"{path}: the archive has no "
                                                 "SystemStructure.ssd at its root")):
        load(path)


UNSUPPORTED = [
    ("ssc:IntegerMappingTransformation",
     {"extra_elements": '<ssd:Component name="Gain" source="resources/gain.fmu"/>',
      "connections": '<ssd:Connections><ssd:Connection startElement="Mass" startConnector="x" '
                     'endElement="Gain" endConnector="u"><ssc:IntegerMappingTransformation>'
                     '<ssc:MapEntry source="1" target="2"/></ssc:IntegerMappingTransformation>'
                     '</ssd:Connection></ssd:Connections>'}),
    ("component type 'application/x-ssp-package'",
     {"extra_elements": '<ssd:Component name="Inner" type="application/x-ssp-package" '
                        'source="inner.ssp"/>'}),
    ("annotation type 'org.example.tool'",
     {"experiment": '<ssd:DefaultExperiment><ssd:Annotations><ssc:Annotation '
                    'type="org.example.tool"><x/></ssc:Annotation></ssd:Annotations>'
                    '</ssd:DefaultExperiment>'}),
    ("connector kind 'calculatedParameter' on a component",
     {"connectors": X_OUTPUT + '<ssd:Connector name="e" kind="calculatedParameter">'
                               '<ssc:Real/></ssd:Connector>'}),
    ("a connection from an output to a parameter connector",
     {"connectors": X_OUTPUT + '<ssd:Connector name="mu" kind="parameter"><ssc:Real/>'
                               '</ssd:Connector>',
      "connections": '<ssd:Connections><ssd:Connection startElement="Mass" startConnector="x" '
                     'endElement="Mass" endConnector="mu"/></ssd:Connections>'}),
]


@pytest.mark.parametrize(("kind", "parts"), UNSUPPORTED, ids=[u[0] for u in UNSUPPORTED])
def test_each_unsupported_element_warns_once_naming_it(tmp_path: Path, kind: str,
                                                       parts: dict[str, str]) -> None:
    path = one_mass(tmp_path, **parts)
    with zipfile.ZipFile(path, "a") as archive:
        archive.write(Path(__import__("syssimx").fmus.path("gain")), "resources/gain.fmu")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        load(path)
    messages = [str(w.message) for w in caught if issubclass(w.category, SSPWarning)]
    assert messages == [m for m in messages if m.startswith(
        f"{kind} is not supported and is ignored: {path}:SystemStructure.ssd: <")]
    assert len(messages) == 1


@pytest.mark.parametrize("source", ["../outside.fmu", "/etc/hostname", "resources/../../x.fmu"])
def test_a_source_outside_the_archive_is_refused(tmp_path: Path, source: str) -> None:
    system = (f'<ssd:System name="s"><ssd:Elements><ssd:Component name="Far" '
              f'source="{source}"/></ssd:Elements></ssd:System>')
    path = write_ssp(tmp_path / "s.ssp", ssd(system))
    with pytest.raises(SSPError, match=re.escape(f"{path}:SystemStructure.ssd: <Component "
                                                 f"'Far'> (line 3): source {source!r} lies "
                                                 "outside the archive")):
        load(path)


@pytest.mark.parametrize("kind", ["FMU", "SSV"])
def test_a_plain_ssd_refuses_an_absolute_source(tmp_path: Path, kind: str) -> None:
    """Before: a plain .ssd read an FMU or .ssv by its absolute path, from any folder."""
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    shutil.copy(fmus.path("sliding_mass"), elsewhere / "sliding_mass.fmu")
    (elsewhere / "p.ssv").write_text(
        '<ssv:ParameterSet xmlns:ssv="http://ssp-standard.org/SSP1/'
        'SystemStructureParameterValues" version="1.0" name="p"><ssv:Parameters/>'
        '</ssv:ParameterSet>')
    folder = tmp_path / "system"
    (folder / "resources").mkdir(parents=True)
    shutil.copy(fmus.path("sliding_mass"), folder / "resources" / "sliding_mass.fmu")
    source = str(elsewhere / ("sliding_mass.fmu" if kind == "FMU" else "p.ssv"))
    mass = MASS.format(connectors=X_OUTPUT)
    if kind == "FMU":
        mass = mass.replace("resources/sliding_mass.fmu", source)
        bindings, element = "", "<Component 'Mass'> (line 3)"
    else:
        bindings = (f'<ssd:ParameterBindings><ssd:ParameterBinding source="{source}"/>'
                    '</ssd:ParameterBindings>')
        element = "<ParameterBinding> (line 3)"
    path = folder / "SystemStructure.ssd"
    path.write_text(ssd(f'<ssd:System name="s">{bindings}<ssd:Elements>{mass}</ssd:Elements>'
                        '</ssd:System>'))
    with pytest.raises(SSPError) as caught:
        load(path)
    assert str(caught.value) == (f"{path}: {element}: source {source!r} is an absolute path; "
                                 "syssimx reads references relative to the system structure's "
                                 "folder only")
