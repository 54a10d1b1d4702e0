"""A run's event records: copied out of the engine when the run returns, made EventRecords
when first asked for."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from functools import cache
from typing import TYPE_CHECKING, Any

import numpy as np

from ..engine import enum_name, ffi, lib
from .event_record import EventRecord, LocalizationTrial

if TYPE_CHECKING:
    from ..bridge.plan import EnginePlan

_RECORD_FIELDS = ("t", "micro", "indicator", "component", "own", "iterations", "rollbacks",
                  "do_steps", "t_left", "t_right", "value_left", "value_right", "first_trial",
                  "n_trials", "clock")
_TRIAL_FIELDS = ("t", "a", "b", "value")


@cache
def _struct_dtype(ctype: str) -> np.dtype:
    """The numpy dtype of the engine's struct `ctype`, laid out as the compiler laid it out."""
    names, formats, offsets = [], [], []
    for name, field in ffi.typeof(ctype).fields:
        size = ffi.sizeof(field.type)
        kind = "f" if field.type.cname in ("double", "float") else \
            "u" if field.type.cname.startswith(("unsigned", "size_t", "uint")) else "i"
        names.append(name)
        formats.append(np.dtype(f"{kind}{size}"))
        offsets.append(field.offset)
    return np.dtype({"names": names, "formats": formats, "offsets": offsets,
                     "itemsize": ffi.sizeof(ctype)})


def _copied(copy: Any, plan: EnginePlan, ctype: str, count: int) -> np.ndarray | None:
    """The engine's first `count` structs `ctype`, copied by `copy` in one call, as a numpy
    record array that owns its memory (later runs do not change it); None for none."""
    if count == 0:
        return None
    block = ffi.new(f"{ctype}[]", count)
    copied = int(copy(plan.sys, 0, count, block))
    return np.frombuffer(ffi.buffer(block), dtype=_struct_dtype(ctype), count=copied).copy()


def _own_event_kind(component: int, own: int, clock: int) -> str:
    return enum_name("ssx_own_event_kind", "SSX_OWN_", own)


def _rows(array: np.ndarray | None, fields: tuple[str, ...]) -> list[tuple[Any, ...]]:
    """The structs as rows of Python numbers in the order of `fields`."""
    if array is None:
        return []
    return list(zip(*(array[name].tolist() for name in fields), strict=True))


class RecordedEvents:
    """The events since initialize and their localization trials, as the engine held them when
    the run returned (two copies, no Python per event), made EventRecords when `made()` is
    first called: a run whose events nobody reads costs no Python object per event."""

    def __init__(self, plan: EnginePlan | None = None, count: int = 0,
                 made: Sequence[EventRecord] = ()) -> None:
        """From the engine of `plan` (`count` records, when the caller knows), or from records
        already `made`."""
        self._made: list[EventRecord] | None = list(made)
        self._records: np.ndarray | None = None
        self._trials: np.ndarray | None = None
        self._indicators: list[tuple[str, str]] = []
        self._index: Mapping[str, int] = {}
        self._own_event_name: Callable[[int, int, int], str] = _own_event_kind
        if plan is None:
            return
        engine = lib()
        self._records = _copied(engine.ssx_events_copy, plan, "ssx_event_record", count)
        if self._records is None:
            return
        self._trials = _copied(engine.ssx_event_trials_copy, plan, "ssx_localization_trial",
                               int(engine.ssx_event_trial_count(plan.sys)))
        # the plan's tables, which a plan keeps as built (a new structure makes a new plan)
        self._indicators, self._index = plan.indicators, plan.index
        self._own_event_name = plan.own_event_name
        self._made = None

    def made(self) -> list[EventRecord]:
        """The EventRecords, made on the first call."""
        if self._made is None:
            self._made = self._make()
            self._records = self._trials = None
        return self._made

    def _make(self) -> list[EventRecord]:
        trials = [LocalizationTrial(*row) for row in _rows(self._trials, _TRIAL_FIELDS)]
        names: list[str] = []
        events = []
        for (t, micro, indicator, component, own, iterations, rollbacks, do_steps, t_left,
             t_right, value_left, value_right, first_trial, n_trials, clock) in _rows(
                 self._records, _RECORD_FIELDS):
            if indicator >= 0:
                source, event = self._indicators[indicator]
            else:
                names = names or list(self._index)
                source = names[component]
                event = self._own_event_name(component, own, clock)
            events.append(EventRecord(
                t, micro, source, event, iterations, rollbacks, do_steps, t_left, t_right,
                value_left, value_right, tuple(trials[first_trial:first_trial + n_trials]),
                indicator < 0))
        return events


def as_recorded(events: RecordedEvents | Sequence[EventRecord]) -> RecordedEvents:
    """`events` as RecordedEvents (records already made are wrapped)."""
    return events if isinstance(events, RecordedEvents) else RecordedEvents(made=events)
