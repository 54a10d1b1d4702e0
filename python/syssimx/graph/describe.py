"""The text report of a system's structure that ``System.describe()`` prints."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from .analysis import analyze_system
from .ports import port_label, unit_text


def describe_system(system: Any) -> str:
    """Components (group, ports with units, feedthrough), connections with units, event
    connections, execution order and algebraic loops of ``system``."""
    analysis = analyze_system(system)
    components: Mapping[str, Any] = system.components
    connections = list(system.connections)
    event_connections = list(getattr(system, "event_connections", []))

    lines = [
        f"System {getattr(system, 'name', '')!r}: {_count(len(components), 'component')}, "
        f"{_count(len(connections), 'connection')}, "
        f"{_count(len(event_connections), 'event connection')}",
        "Components:",
    ]
    for name, component in components.items():
        group = getattr(component, "group", None)
        lines.append(f"  {name}" + (f"  (group {group})" if group else ""))
        lines.append(f"    inputs:  {_ports(component.input_specs)}")
        lines.append(f"    outputs: {_ports(component.output_specs)}")
        feedthrough = getattr(component, "direct_feedthrough", None) or {}
        for output, inputs in feedthrough.items():
            if inputs:
                lines.append(f"    feedthrough: {output} <- {', '.join(sorted(inputs))}")

    lines.append("Connections:")
    for c in connections:
        src_unit = _unit_of(components, c.src_comp, c.src_port, "output_specs")
        dst_unit = _unit_of(components, c.dst_comp, c.dst_port, "input_specs")
        lines.append(
            f"  {c.src_comp}.{c.src_port}{_bracket(src_unit)} -> "
            f"{c.dst_comp}.{c.dst_port}{_bracket(dst_unit)}"
        )
    if not connections:
        lines.append("  none")

    lines.append("Event connections:")
    for c in event_connections:
        lines.append(f"  {c.src_comp}.{c.src_port} -> {c.dst_comp}.{c.dst_port}")
    if not event_connections:
        lines.append("  none")

    loop_members = {name for loop in analysis.loops for name in loop}
    lines.append("Execution order (Gauss-Seidel generations):")
    for index, generation in enumerate(analysis.generations, start=1):
        marked = [f"{name}*" if name in loop_members else name for name in generation]
        lines.append(f"  {index}: {', '.join(marked)}")

    lines.append("Algebraic loops:" + ("" if analysis.loops else " none"))
    for loop in analysis.loops:
        members = set(loop)
        tears = [
            f"{src}.{src_port} -> {dst}.{dst_port}"
            for src, src_port, dst, dst_port in analysis.loop_connections
            if src in members
        ]
        lines.append(f"  * {', '.join(loop)}: {'; '.join(tears)}")
    if analysis.delayed_connections:
        lines.append("Cycles of components without a cycle of variables (no loop; these "
                     "connections carry their value of the step's start):")
        lines.extend(f"  {src}.{src_port} -> {dst}.{dst_port}"
                     for src, src_port, dst, dst_port in analysis.delayed_connections)
    undeclared = [name for name, component in components.items()
                  if getattr(component, "undeclared_outputs", lambda: set())()]
    if undeclared:
        choice = ("all inputs (the standard; a loop this makes is solved)"
                  if analysis.undeclared_dependencies == "all" else
                  "no input (coupled explicitly, like libcosim)")
        lines.append(f"Undeclared output dependencies ({', '.join(undeclared)}): taken as "
                     f"{choice}; undeclared_dependencies={analysis.undeclared_dependencies!r}")
        if analysis.undeclared_in_loops:
            lines.append("  loops made by that assumption: "
                         + ", ".join(analysis.undeclared_in_loops))
    return "\n".join(lines)


def _ports(specs: Mapping[str, Any]) -> str:
    return ", ".join(port_label(spec) for spec in specs.values()) if specs else "none"


def _unit_of(components: Mapping[str, Any], comp: str, port: str, side: str) -> str | None:
    spec = getattr(components[comp], side).get(port)
    return unit_text(spec.unit) if spec is not None else None


def _bracket(unit: str | None) -> str:
    return f" [{unit}]" if unit else ""


def _count(n: int, noun: str) -> str:
    return f"{n} {noun}" + ("" if n == 1 else "s")
