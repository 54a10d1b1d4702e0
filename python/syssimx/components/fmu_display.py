"""How an FMU component shows: one line of text (repr) and an HTML table for a notebook, with
its FMU file, FMI version, the interface it runs and its ports with their units. A large FMI
3.0 array is not listed element by element: the first ports are shown and the rest counted."""

from __future__ import annotations

import html
from collections.abc import Mapping
from itertools import islice
from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    from ..core.port import PortSpec
    from ..fmu.info import FMUInfo, FMUInterface


class ShownFMU(Protocol):
    """What the display reads of an FMU component (the component module imports this one)."""

    @property
    def name(self) -> str: ...
    @property
    def info(self) -> FMUInfo: ...
    @property
    def fmu_interface(self) -> FMUInterface: ...
    @property
    def input_specs(self) -> Mapping[str, PortSpec]: ...
    @property
    def output_specs(self) -> Mapping[str, PortSpec]: ...

SHOWN_PORTS = 12  # per direction


def port_label(spec: PortSpec) -> str:
    """"name [unit]", or the name alone when the port has no unit."""
    return f"{spec.name} [{spec.unit}]" if spec.unit else spec.name


def port_labels(specs: Mapping[str, PortSpec]) -> list[str]:
    """The first SHOWN_PORTS ports' labels, then "... N more" for the rest."""
    labels = [port_label(spec) for spec in islice(specs.values(), SHOWN_PORTS)]
    if len(specs) > SHOWN_PORTS:
        labels.append(f"... {len(specs) - SHOWN_PORTS} more")
    return labels


def component_text(component: ShownFMU) -> str:
    fmu = component.info.path.name
    return (f"FMUComponent({component.name!r}, {fmu}, {component.info.standard.name} "
            f"{component.fmu_interface.name}, "
            f"inputs: {', '.join(port_labels(component.input_specs)) or 'none'}; "
            f"outputs: {', '.join(port_labels(component.output_specs)) or 'none'})")


def component_html(component: ShownFMU) -> str:
    def row(header: str, value: str) -> str:
        return f"<tr><th>{html.escape(header)}</th><td>{html.escape(value)}</td></tr>"

    return ("<table><caption>FMUComponent " + html.escape(repr(component.name)) + "</caption>"
            + row("FMU", str(component.info.path))
            + row("FMI version", component.info.standard.version)
            + row("interface", component.fmu_interface.name)
            + row("inputs", ", ".join(port_labels(component.input_specs)) or "none")
            + row("outputs", ", ".join(port_labels(component.output_specs)) or "none")
            + "</table>")
