"""The picture and the report of systems built with the real API and the bundled FMUs."""

from __future__ import annotations

import shutil
import xml.etree.ElementTree as ET

import pytest
from syssimx import Connection, EventConnection, FMUComponent, PortSpec, PortType, System, fmus
from syssimx.graph.describe import describe_system
from syssimx.viz.system_graph_visualizer import (
    EVENT_COLOR,
    LOOP_COLOR,
    SystemGraphVisualizer,
    system_svg,
)

pytestmark = pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz 'dot' missing")

SVG = "{http://www.w3.org/2000/svg}"


def edge_strokes(svg: str) -> dict[str, str | None]:
    root = ET.fromstring(svg)
    strokes = {}
    for g in root.iter(f"{SVG}g"):
        if g.get("class", "").startswith("edge"):
            path = g.find(f"{SVG}path")
            strokes[g.get("id")] = path.get("stroke") if path is not None else None
    return strokes


def test_seed_system_shows_the_wall_event_edge() -> None:
    # The seed's wiring: an indicator on theta, an event input, an event connection to itself.
    pendulum = FMUComponent("Pendulum_Euler", fmus.path("pendulum_euler"), group="Mechanical")
    pendulum.input_specs["omega_invert"] = PortSpec("omega_invert", PortType.EVENT, "in")
    pendulum.add_event_indicator("wall_hit", variable="theta", direction=-1)
    system = System(name="System - Euler")
    system.add_component(pendulum)
    system.add_event_connection(
        EventConnection("Pendulum_Euler", "wall_hit", "Pendulum_Euler", "omega_invert"))

    svg = system_svg(system)
    assert edge_strokes(svg) == {
        "event:Pendulum_Euler.wall_hit->Pendulum_Euler.omega_invert": EVENT_COLOR}
    text = ["".join(t.itertext()) for t in ET.fromstring(svg).iter(f"{SVG}text")]
    for label in ("Pendulum_Euler", "Mechanical", "torque [N.m]", "theta [rad]",
                  "omega [rad/s]", "alpha [rad/s2]", "wall_hit (event)",
                  "omega_invert (event)"):
        assert label in text
    assert SystemGraphVisualizer(system).visualize().source.startswith("digraph")


def test_gain_and_sum_fmus_form_a_highlighted_loop() -> None:
    gain, summer = FMUComponent("Gain", fmus.path("gain")), FMUComponent("Sum", fmus.path("sum"))
    system = System("loop")
    for component in (gain, summer):
        system.add_component(component)
    system.add_connection(Connection("Gain", "y", "Sum", "u"))
    system.add_connection(Connection("Sum", "y", "Gain", "u"))

    assert edge_strokes(system_svg(system)) == {
        "connection:Gain.y->Sum.u": LOOP_COLOR,
        "connection:Sum.y->Gain.u": LOOP_COLOR,
    }
    report = describe_system(system).splitlines()
    assert report[-3:] == ["  1: Gain*, Sum*", "Algebraic loops:",
                           "  * Gain, Sum: Gain.y -> Sum.u; Sum.y -> Gain.u"]
    # The FMUs' ModelStructure says y <- u for both.
    assert "    feedthrough: y <- u" in report
