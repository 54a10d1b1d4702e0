"""FMI 3.0 clocks as a description declares them: each `<Clock>` variable, the clocks of each
clocked variable, and the ModelStructure dependencies that involve clocks.

FMPy 0.3 reads a Clock as a plain variable and drops its interval, shift, priority and
`clocks` attributes, so they are read here from the XML. A description is data: a clock with
an unknown intervalVariability, an interval that is not a positive number, or a `clocks`
reference that names no clock is an FMUFileError naming the file and the variable.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import FMUFileError

INTERVAL_VARIABILITIES = ("constant", "fixed", "tunable", "changing", "countdown", "triggered")
# clocks whose ticks follow from their interval and shift, known before the run
TIME_BASED = ("constant", "fixed", "tunable", "changing", "countdown")
# ModelStructure elements whose dependencies may name clocks
_STRUCTURE_ELEMENTS = ("Output", "ContinuousStateDerivative", "ClockedState",
                       "InitialUnknown", "EventIndicator")


@dataclass(frozen=True)
class ClockInfo:
    """One `<Clock>` variable. Intervals and shifts are in seconds (intervalDecimal,
    shiftDecimal) or in counts of 1/resolution seconds (intervalCounter, shiftCounter); None
    where the description does not give them."""

    name: str
    value_reference: int
    causality: str  # "input", "output" or "local"
    interval_variability: str  # one of INTERVAL_VARIABILITIES
    interval: float | None = None
    shift: float = 0.0
    interval_counter: int | None = None
    shift_counter: int = 0
    resolution: int | None = None
    priority: int | None = None
    supports_fraction: bool = False
    can_be_deactivated: bool = False
    clocks: tuple[int, ...] = ()  # the clocks this clock is triggered by ("clocks" attribute)

    @property
    def period(self) -> float | None:
        """Seconds between ticks when the description fixes them (intervalDecimal, or
        intervalCounter / resolution); None otherwise."""
        if self.interval is not None:
            return self.interval
        if self.interval_counter is not None and self.resolution:
            return self.interval_counter / self.resolution
        return None

    @property
    def first_tick(self) -> float:
        """Seconds after the start of the first tick of a periodic clock (its shift)."""
        if self.shift_counter and self.resolution:
            return self.shift_counter / self.resolution
        return self.shift


@dataclass(frozen=True)
class ClockStructure:
    """The clocks of one FMU and what depends on them."""

    clocks: tuple[ClockInfo, ...] = ()
    # variable name -> value references of the clocks it is clocked by
    clocked_variables: Mapping[str, tuple[int, ...]] = field(default_factory=dict)
    # ModelStructure: value reference of an unknown -> its dependencies, for every unknown
    # that is a clock, is clocked, or depends on a clock
    dependencies: Mapping[int, tuple[int, ...]] = field(default_factory=dict)
    # ModelStructure/ClockedState value references
    clocked_states: tuple[int, ...] = ()

    def by_name(self, name: str) -> ClockInfo:
        """The clock called `name`; KeyError naming the clocks there are."""
        for clock in self.clocks:
            if clock.name == name:
                return clock
        raise KeyError(f"no clock {name!r} (clocks: {', '.join(c.name for c in self.clocks)})")

    def by_reference(self, value_reference: int) -> ClockInfo:
        for clock in self.clocks:
            if clock.value_reference == value_reference:
                return clock
        raise KeyError(f"no clock has value reference {value_reference}")


def read_clocks(root: Any, path: Path) -> ClockStructure:
    """The ClockStructure of the description whose XML root element is `root` (of the FMU
    archive `path`, for messages)."""
    variables = root.find("ModelVariables")
    if variables is None:
        return ClockStructure()
    clocks = tuple(_clock(element, path) for element in variables.findall("Clock"))
    references = {clock.value_reference for clock in clocks}
    clocked: dict[str, tuple[int, ...]] = {}
    for element in variables:
        if not isinstance(element.tag, str):  # comments
            continue
        text = element.get("clocks")
        if text is None:
            continue
        name = element.get("name", "")
        found = _references(text, path, name, "clocks")
        unknown = [vr for vr in found if vr not in references]
        if unknown:
            raise FMUFileError(f"{path}: variable {name!r} is clocked by value reference "
                               f"{unknown[0]}, which is no Clock")
        if element.tag != "Clock":
            clocked[name] = found
    dependencies: dict[int, tuple[int, ...]] = {}
    clocked_states: list[int] = []
    clocked_references = {int(e.get("valueReference", "-1")) for e in variables
                          if isinstance(e.tag, str) and e.get("clocks") is not None}
    structure = root.find("ModelStructure")
    for element in structure if structure is not None else ():
        if element.tag not in _STRUCTURE_ELEMENTS:
            continue
        vr = _reference(element.get("valueReference"), path, element.tag)
        if element.tag == "ClockedState":
            clocked_states.append(vr)
        depends = _references(element.get("dependencies", ""), path, element.tag,
                              "dependencies")
        if vr in references or vr in clocked_references or references.intersection(depends):
            dependencies[vr] = depends
    return ClockStructure(clocks, clocked, dependencies, tuple(clocked_states))


def _clock(element: Any, path: Path) -> ClockInfo:
    name = element.get("name", "")
    vr = _reference(element.get("valueReference"), path, name)
    variability = element.get("intervalVariability")
    if variability not in INTERVAL_VARIABILITIES:
        raise FMUFileError(f"{path}: Clock {name!r} has intervalVariability {variability!r}; "
                           f"FMI 3.0 allows {', '.join(INTERVAL_VARIABILITIES)}")
    interval = _seconds(element.get("intervalDecimal"), path, name, "intervalDecimal",
                        positive=True)
    shift = _seconds(element.get("shiftDecimal"), path, name, "shiftDecimal", positive=False)
    return ClockInfo(
        name=name, value_reference=vr, causality=element.get("causality", "local"),
        interval_variability=variability, interval=interval,
        shift=0.0 if shift is None else shift,
        interval_counter=_count(element.get("intervalCounter"), path, name, "intervalCounter"),
        shift_counter=_count(element.get("shiftCounter"), path, name, "shiftCounter") or 0,
        resolution=_count(element.get("resolution"), path, name, "resolution"),
        priority=_count(element.get("priority"), path, name, "priority"),
        supports_fraction=element.get("supportsFraction") in ("true", "1"),
        can_be_deactivated=element.get("canBeDeactivated") in ("true", "1"),
        clocks=_references(element.get("clocks", ""), path, name, "clocks"))


def _seconds(text: str | None, path: Path, name: str, attribute: str, *,
             positive: bool) -> float | None:
    if text is None:
        return None
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value) or value < 0 or (positive and value == 0):
        raise FMUFileError(f"{path}: Clock {name!r} has {attribute}={text[:40]!r}; it is a "
                           f"{'positive' if positive else 'non-negative'} number of seconds")
    return value


def _count(text: str | None, path: Path, name: str, attribute: str) -> int | None:
    if text is None:
        return None
    if not text.strip().isdigit():
        raise FMUFileError(f"{path}: Clock {name!r} has {attribute}={text[:40]!r}; it is a "
                           "whole number 0 or more")
    return int(text)


def _reference(text: str | None, path: Path, where: str) -> int:
    if text is None or not text.strip().isdigit():
        raise FMUFileError(f"{path}: {where!r} has valueReference {text!r}, not a whole number")
    return int(text)


def _references(text: str, path: Path, where: str, attribute: str) -> tuple[int, ...]:
    words = text.split()
    if not all(word.isdigit() for word in words):
        raise FMUFileError(f"{path}: {where!r} has {attribute}={text[:40]!r}; it lists value "
                           "references")
    return tuple(int(word) for word in words)
