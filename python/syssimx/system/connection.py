"""Connections between components: data (output -> input) and event (event source ->
listener)."""

from __future__ import annotations

from dataclasses import dataclass

from ..core.events import OWN_EVENTS


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
    """The events of `src_port` (an event indicator of src_comp, or ``"own_events"``: the
    events an FMU component handles inside its own steps) are delivered to dst_comp through its
    EVENT input dst_port; dst_comp handles them (its handler or _handle_events_internal).

    An indicator's listeners run at the located event time. Own events' listeners run when the
    master accepts the step that holds the event: a handler receives the event's own time,
    while the system stands at the step's end (a Reinitialize restarts there).
    """

    src_comp: str
    src_port: str
    dst_comp: str
    dst_port: str

    @classmethod
    def own_events(cls, src_comp: str, dst_comp: str, dst_port: str) -> EventConnection:
        """The events src_comp handles inside its own steps, delivered to dst_comp.dst_port."""
        return cls(src_comp, OWN_EVENTS, dst_comp, dst_port)

    @property
    def event_name(self) -> str:
        return self.src_port

    def key(self) -> tuple[str, str, str, str]:
        return (self.src_comp, self.src_port, self.dst_comp, self.dst_port)
