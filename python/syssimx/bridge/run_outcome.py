"""What System.run reads of the engine after a run, in one engine call.

Every call across cffi costs about as much as a short Python function, and a run of a few
steps is read by several (the time, the events, the termination, the statistics, the
history): ssx_get_run_outcome reads them at once.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..engine import ffi, lib
from .history_arrays import HistoryArrays

if TYPE_CHECKING:
    from .plan import EnginePlan


class RunOutcome:
    """The engine's state after a run: `time` reached, `event_count` (events since
    initialize), `termination` and `statistics` (its C structs) and `history`, the arrays of
    every sample so far (retained: they stay that run's whatever the system does next)."""

    def __init__(self, plan: EnginePlan) -> None:
        self._raw = raw = ffi.new("ssx_run_outcome *")
        lib().ssx_get_run_outcome(plan.sys, raw)
        # the history reference belongs to the arrays from here on (released with them)
        self.history = HistoryArrays.of_retained(raw.history, int(raw.history_length),
                                                 raw.history_time, raw.history_micro,
                                                 plan.release_history, plan.tabled_values())
        self.time = float(raw.time)
        self.event_count = int(raw.n_events)
        self.termination = raw.termination
        # a struct inside the outcome: whoever reads it later keeps `owner` alive with it
        self.statistics = raw.statistics
        self.owner = raw
