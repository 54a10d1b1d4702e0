"""The system picture: rendered by Graphviz to SVG and read back with xml.etree."""

from __future__ import annotations

import itertools
import shutil
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path

import pytest
from syssimx.graph.describe import describe_system
from syssimx.viz.system_graph_visualizer import (
    EVENT_COLOR,
    LOOP_COLOR,
    SystemGraphVisualizer,
    system_svg,
)

pytestmark = pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz 'dot' missing")

SVG = "{http://www.w3.org/2000/svg}"


class Kind(StrEnum):
    REAL = "real"
    EVENT = "event"


@dataclass(frozen=True)
class Spec:
    name: str
    type: Kind
    direction: str
    unit: str | None = None


@dataclass
class Component:
    group: str | None
    inputs: list[Spec]
    outputs: list[Spec]
    direct_feedthrough: dict[str, set[str]] = field(default_factory=dict)

    @property
    def input_specs(self) -> dict[str, Spec]:
        return {spec.name: spec for spec in self.inputs}

    @property
    def output_specs(self) -> dict[str, Spec]:
        return {spec.name: spec for spec in self.outputs}


@dataclass(frozen=True)
class Link:
    src_comp: str
    src_port: str
    dst_comp: str
    dst_port: str


@dataclass
class System:
    name: str
    components: dict[str, Component]
    connections: list[Link]
    event_connections: list[Link]


def real(name: str, direction: str, unit: str | None = None) -> Spec:
    return Spec(name, Kind.REAL, direction, unit)


def sample_system() -> System:
    """A pendulum with a wall event, a sensor in centimetres and a gain/sum algebraic loop."""
    pendulum = Component(
        "Mechanical",
        [real("torque", "in", "N.m"), Spec("omega_invert", Kind.EVENT, "in")],
        [real("theta", "out", "rad"), real("x", "out", "m"), Spec("wall_hit", Kind.EVENT, "out")],
    )
    sensor = Component("Signals", [real("position", "in", "cm")], [real("reading", "out")])
    gain = Component("Signals", [real("u", "in")], [real("y", "out")], {"y": {"u"}})
    summer = Component(None, [real("u", "in"), real("w", "in")], [real("y", "out")],
                       {"y": {"u", "w"}})
    return System(
        "Demo <system>",
        {"Pendulum": pendulum, "Sensor": sensor, "Gain": gain, "Sum": summer},
        [
            Link("Pendulum", "x", "Sensor", "position"),
            Link("Sensor", "reading", "Sum", "w"),
            Link("Sum", "y", "Gain", "u"),
            Link("Gain", "y", "Sum", "u"),
        ],
        [Link("Pendulum", "wall_hit", "Pendulum", "omega_invert")],
    )


def edges_by_id(svg: str) -> dict[str, ET.Element]:
    root = ET.fromstring(svg)
    return {g.get("id"): g for g in root.iter(f"{SVG}g") if g.get("class", "").startswith("edge")}


def texts(element: ET.Element) -> list[str]:
    return ["".join(t.itertext()) for t in element.iter(f"{SVG}text")]


def stroke_of(edge: ET.Element) -> tuple[str | None, str | None, str | None]:
    path = edge.find(f"{SVG}path")
    assert path is not None
    return path.get("stroke"), path.get("stroke-dasharray"), path.get("stroke-width")


def test_every_component_port_and_connection_is_drawn() -> None:
    system = sample_system()
    svg = system_svg(system)
    root = ET.fromstring(svg)
    nodes = {g.get("id"): g for g in root.iter(f"{SVG}g") if g.get("class") == "node"}
    assert set(nodes) == {f"component:{name}" for name in system.components}
    pendulum_text = texts(nodes["component:Pendulum"])
    for label in ("Pendulum", "torque [N.m]", "omega_invert (event)", "theta [rad]", "x [m]",
                  "wall_hit (event)"):
        assert label in pendulum_text
    all_text = texts(root)
    assert "Mechanical" in all_text and "Signals" in all_text  # group clusters
    assert any("Demo <system>" in text for text in all_text)  # escaped and read back intact

    edges = edges_by_id(svg)
    expected = {f"connection:{c.src_comp}.{c.src_port}->{c.dst_comp}.{c.dst_port}"
                for c in system.connections}
    expected.add("event:Pendulum.wall_hit->Pendulum.omega_invert")
    assert set(edges) == expected
    assert texts(edges["connection:Pendulum.x->Sensor.position"]) == ["m -> cm"]


def test_event_edges_are_dashed_in_the_event_colour() -> None:
    edges = edges_by_id(system_svg(sample_system()))
    edge = edges["event:Pendulum.wall_hit->Pendulum.omega_invert"]
    stroke, dashes, _ = stroke_of(edge)
    assert stroke == EVENT_COLOR
    assert dashes is not None


def test_loop_edges_are_highlighted_and_the_others_are_not() -> None:
    edges = edges_by_id(system_svg(sample_system()))
    for loop_edge in ("connection:Sum.y->Gain.u", "connection:Gain.y->Sum.u"):
        stroke, dashes, width = stroke_of(edges[loop_edge])
        assert (stroke, dashes, width) == (LOOP_COLOR, None, "2.5")
        assert "loop" in edges[loop_edge].get("class", "")
    stroke, _, width = stroke_of(edges["connection:Sensor.reading->Sum.w"])
    assert stroke != LOOP_COLOR and width is None


def test_save_and_visualize_write_files(tmp_path: Path) -> None:
    visualizer = SystemGraphVisualizer(sample_system())
    png = visualizer.save(tmp_path / "system.png")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    source = visualizer.save(tmp_path / "system.gv")
    assert source.read_text().startswith("digraph")
    drawing = visualizer.visualize(str(tmp_path / "seed"), format="svg")
    assert (tmp_path / "seed.svg").is_file()
    assert drawing.source == visualizer.graph().source
    with pytest.raises(ValueError, match="suffix"):
        visualizer.save(tmp_path / "no_suffix")


def test_describe_reports_units_groups_order_and_loops() -> None:
    report = describe_system(sample_system())
    assert report.splitlines() == [
        "System 'Demo <system>': 4 components, 4 connections, 1 event connection",
        "Components:",
        "  Pendulum  (group Mechanical)",
        "    inputs:  torque [N.m], omega_invert (event)",
        "    outputs: theta [rad], x [m], wall_hit (event)",
        "  Sensor  (group Signals)",
        "    inputs:  position [cm]",
        "    outputs: reading",
        "  Gain  (group Signals)",
        "    inputs:  u",
        "    outputs: y",
        "    feedthrough: y <- u",
        "  Sum",
        "    inputs:  u, w",
        "    outputs: y",
        "    feedthrough: y <- u, w",
        "Connections:",
        "  Pendulum.x [m] -> Sensor.position [cm]",
        "  Sensor.reading -> Sum.w",
        "  Sum.y -> Gain.u",
        "  Gain.y -> Sum.u",
        "Event connections:",
        "  Pendulum.wall_hit -> Pendulum.omega_invert",
        "Execution order (Gauss-Seidel generations):",
        "  1: Sensor, Pendulum",
        "  2: Gain*, Sum*",
        "Algebraic loops:",
        "  * Gain, Sum: Sum.y -> Gain.u; Gain.y -> Sum.u",
    ]


HOSTILE_NAMES = ("<A>", "B\\", 'C"q', "<D\\>", "E\\n")


def test_names_with_dot_syntax_are_drawn_as_they_are() -> None:
    """Before: graphviz's "syntax error" for a name in <...> (read as an HTML label) or with a
    trailing backslash (which escaped the closing quote)."""
    components = {name: Component("<G>\\", [real(f"in{name}", "in")], [real(f"out{name}", "out")])
                  for name in HOSTILE_NAMES}
    links = [Link(a, f"out{a}", b, f"in{b}")
             for a, b in itertools.pairwise(HOSTILE_NAMES)]
    svg = system_svg(System("<S>\\", components, links, []))
    root = ET.fromstring(svg)
    nodes = {g.get("id") for g in root.iter(f"{SVG}g") if g.get("class") == "node"}
    assert nodes == {f"component:{name}" for name in HOSTILE_NAMES}
    assert set(edges_by_id(svg)) == {f"connection:{c.src_comp}.{c.src_port}->{c.dst_comp}."
                                     f"{c.dst_port}" for c in links}
    all_text = texts(root)
    for name in HOSTILE_NAMES:
        assert name in all_text and f"out{name}" in all_text
    assert "<G>\\" in all_text and any(text.startswith("<S>\\") for text in all_text)


def test_a_drawing_dot_refuses_is_a_runtime_error_a_display_catches(
        monkeypatch: pytest.MonkeyPatch) -> None:
    import graphviz

    def refuse(*args: object, **kwargs: object) -> str:
        raise graphviz.CalledProcessError(1, ["dot"], stderr="syntax error in line 1")

    monkeypatch.setattr(graphviz.Digraph, "pipe", refuse)
    with pytest.raises(RuntimeError, match="Graphviz's dot could not draw 'Demo <system>': "
                                           "syntax error in line 1"):
        system_svg(sample_system())
