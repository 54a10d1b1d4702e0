"""Event vocabulary: superdense time instants, event indicator declarations and the name of
a component's own events as an event source."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

# The event source port of an FMU component's own events: those it handles inside its step (an
# FMI 3.0 FMU's events, a Model Exchange FMU's state, time and step events).
OWN_EVENTS = "own_events"


@dataclass(frozen=True, order=True)
class DenseTime:
    """A superdense instant: real time t and the micro step of the handling round."""

    t: float
    micro: int = 0

    def __str__(self) -> str:
        return f"({self.t:.8f}, {self.micro})"

    def to_float(self) -> float:
        """The real time (the micro step dropped)."""
        return self.t


@dataclass(frozen=True)
class EventIndicator:
    """A zero-crossing function of a component. Exactly one of `func` (a Python callable of the
    component, evaluated through a callback) and `variable` (an output evaluated in C) is set.
    direction: -1 falling, +1 rising, 0 both."""

    name: str
    direction: int
    func: Callable[[Any], float] | None = None
    variable: str | None = None
