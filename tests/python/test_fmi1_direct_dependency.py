"""FMI 1.0 declares an output's direct dependencies in the output's own
``<DirectDependency><Name>input</Name>...</DirectDependency>``: present, the output depends
directly on exactly the inputs named (empty: on none); absent, on every input. syssimx reads
it where FMI 2.0 and 3.0 have ModelStructure, so a declared output is no undeclared one."""

from __future__ import annotations

import warnings
import zipfile
from pathlib import Path

from fixture_fmus import fmu_path
from syssimx import Connection, FMUComponent, System
from syssimx.errors import SysSimXWarning
from syssimx.graph.analysis import analyze_system

SPRING = "preloaded_spring_fmi1"  # output tau; inputs angle and omega
OUTPUT_START = '<ScalarVariable name="tau"'


def with_direct_dependency(tmp_path: Path, element: str) -> Path:
    """A copy of the spring FMU whose output tau carries `element` (a DirectDependency)."""
    source = Path(fmu_path(SPRING))
    copy = tmp_path / f"{SPRING}.fmu"
    with zipfile.ZipFile(source) as original, zipfile.ZipFile(copy, "w") as rewritten:
        for item in original.infolist():
            data = original.read(item)
            if item.filename == "modelDescription.xml":
                text = data.decode()
                start = text.index(OUTPUT_START)
                end = text.index("</ScalarVariable>", start)
                data = (text[:end] + element + "\n    " + text[end:]).encode()
            rewritten.writestr(item, data)
    return copy


def spring_pair(path: Path | str) -> System:
    """Two springs in a cycle of components: each one's torque drives the other's angle (a
    coupling of structure only: the units differ, so none is converted)."""
    system = System("springs")
    for name in ("a", "b"):
        system.add_component(FMUComponent(name, path))
    system.add_connection(Connection("a", "tau", "b", "angle", convert_units=False))
    system.add_connection(Connection("b", "tau", "a", "angle", convert_units=False))
    return system


def test_an_empty_direct_dependency_makes_an_output_depend_on_no_input(tmp_path: Path):
    component = FMUComponent("spring", with_direct_dependency(tmp_path, "<DirectDependency/>"))
    assert component.direct_feedthrough == {"tau": set()}
    assert component.undeclared_outputs() == set()

    system = spring_pair(component.fmu_path)
    analysis = analyze_system(system)
    assert analysis.loops == []
    assert analysis.undeclared_in_loops == []
    with warnings.catch_warnings():
        warnings.filterwarnings("error", category=SysSimXWarning)
        system.initialize(0.0)
    assert system.run(0.0, 0.01, 0.01).statistics.loop_solves == 0


def test_a_direct_dependency_names_exactly_the_inputs_an_output_depends_on(tmp_path: Path):
    element = "<DirectDependency>\n      <Name> omega </Name>\n    </DirectDependency>"
    component = FMUComponent("spring", with_direct_dependency(tmp_path, element))
    assert component.direct_feedthrough == {"tau": {"omega"}}
    assert component.undeclared_outputs() == set()
    assert analyze_system(spring_pair(component.fmu_path)).loops == []  # angle is not named


def test_without_direct_dependency_an_output_depends_on_every_input():
    component = FMUComponent("spring", fmu_path(SPRING))
    assert component.direct_feedthrough == {"tau": {"angle", "omega"}}
    assert component.undeclared_outputs() == {"tau"}
    analysis = analyze_system(spring_pair(fmu_path(SPRING)))
    assert [sorted(loop) for loop in analysis.loops] == [["a", "b"]]
    assert sorted(analysis.undeclared_in_loops) == ["a", "b"]


def test_a_direct_dependency_naming_no_variable_leaves_the_output_undeclared(tmp_path: Path):
    element = "<DirectDependency><Name>nowhere</Name></DirectDependency>"
    component = FMUComponent("spring", with_direct_dependency(tmp_path, element))
    assert component.direct_feedthrough == {"tau": {"angle", "omega"}}
    assert component.undeclared_outputs() == {"tau"}
