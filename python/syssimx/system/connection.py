"""Connections between components: data (output -> input) and event (indicator -> listener)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Connection:
    """src_comp.src_port (an output) drives dst_comp.dst_port (an input); units are converted.

    `factor` and `offset` transform the value after the unit conversion (in the input's unit):
    dst = factor * converted(src) + offset, an SSP LinearTransformation. With
    `convert_units=False` only the transformation applies (SSP's suppressUnitConversion).
    """

    src_comp: str
    src_port: str
    dst_comp: str
    dst_port: str
    factor: float = 1.0
    offset: float = 0.0
    convert_units: bool = True

    def key(self) -> tuple[str, str, str, str]:
        """(source component, source port, destination component, destination port)."""
        return (self.src_comp, self.src_port, self.dst_comp, self.dst_port)


@dataclass(frozen=True)
class EventConnection:
    """The event `src_port` (an event indicator of src_comp) is delivered to dst_comp through
    its EVENT input dst_port; dst_comp handles it (its handler or _handle_events_internal)."""

    src_comp: str
    src_port: str
    dst_comp: str
    dst_port: str

    @property
    def event_name(self) -> str:
        return self.src_port

    def key(self) -> tuple[str, str, str, str]:
        return (self.src_comp, self.src_port, self.dst_comp, self.dst_port)
