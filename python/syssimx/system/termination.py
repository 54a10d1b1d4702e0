"""Termination: a component asked to end the simulation (fmi2Discard with fmi2Terminated).

The run then ends cleanly at the last communication point the whole system completed; the
engine keeps which component asked and the time it reached.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..engine import ffi, lib

if TYPE_CHECKING:
    from ..bridge.plan import EnginePlan


@dataclass(frozen=True)
class Termination:
    """`component` asked to stop at `time` (its fmi2LastSuccessfulTime); `message` is the FMU's
    last log message ("" if it logged none)."""

    component: str
    time: float
    message: str

    def __str__(self) -> str:
        return f"component {self.component!r} asked to stop at t = {self.time:.12g}"


def read_termination(plan: EnginePlan, raw: Any = None) -> Termination | None:
    """The plan's termination (its ssx_termination `raw`, when the caller has it), or None
    when no component asked to stop."""
    if raw is None:
        raw = lib().ssx_get_termination(plan.sys)
    if raw.component < 0:
        return None
    return Termination(list(plan.index)[raw.component], float(raw.time),
                       ffi.string(raw.message).decode(errors="replace"))
