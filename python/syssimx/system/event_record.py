"""What a run records of its events: each handled event and its localization trials."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..core.events import DenseTime


@dataclass(frozen=True)
class LocalizationTrial:
    """One localization trial: the whole system stepped to t from the bracket's left start;
    [a, b] is the bracket after the trial (t is one of its ends), value the event's indicator
    at t."""

    t: float
    a: float
    b: float
    value: float


@dataclass(frozen=True)
class EventRecord:
    """One handled event: instant (t, micro), source and the localization cost.

    An event a component handled inside its own step (an FMI 3.0 FMU in event mode after an
    early return, a Model Exchange FMU's state, time or step event) is named by its kind:
    "fmu_event", "state_event", "time_event" or "step_event"; it has no localization (0
    iterations, no trials, NaN bracket) and no sample of its own: the other components were
    not at its time.

    For an event located by rollback (micro 0), t_left and t_right are the initial bracket
    (the macro step, or its part after an earlier event, in which the indicator crossed),
    value_left and value_right the indicator there, and trials the localization trials in
    order: one per iteration, brackets nested and shrinking, the last one ending at t. Records
    of one instant share its trials. Cascading events (micro > 0) and a crossing at the very
    start have no trials and NaN bracket values.
    """

    t: float
    micro: int
    component: str
    event: str
    iterations: int
    rollbacks: int
    do_steps: int
    t_left: float = math.nan
    t_right: float = math.nan
    value_left: float = math.nan
    value_right: float = math.nan
    trials: tuple[LocalizationTrial, ...] = ()
    own: bool = False  # handled by its component inside its own step

    @property
    def time(self) -> DenseTime:
        return DenseTime(self.t, self.micro)

    def __repr__(self) -> str:
        """One line; the trials are in `trials` (and `result.events.trials()`)."""
        how = "handled by the component" if self.own else (
            f"{self.iterations} iterations, {len(self.trials)} trials")
        return (f"EventRecord({self.component}.{self.event} at t={self.t!r}, "
                f"micro={self.micro}, {how})")

    @property
    def name(self) -> str:
        return self.event

    @property
    def located_value(self) -> float:
        """The indicator at the located time t (NaN without localization)."""
        for trial in reversed(self.trials):
            if trial.t == self.t:
                return trial.value
        return self.value_right if self.t == self.t_right else math.nan
