"""The hybrid algorithm: event detection, localization by rollback, superdense handling.

The engine does the work in C; this module holds the options and writes the event log from
the engine's event records after a run.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from .coupling import GaussSeidelAlgorithm, JacobiAlgorithm

if TYPE_CHECKING:
    from ..results import EventRecord

logger = logging.getLogger("syssimx.hybrid")

METHODS = ("illinois", "bisection")


@dataclass
class HybridAlgorithm:
    """Options of the hybrid algorithm.

    tol_time: width of the final bracket around an event; tol_value: |indicator| accepted as
    zero; max_iter: localization iterations per event; max_microsteps: handling rounds at one
    instant before a ZenoError; record_internal_steps: also record the localization trials;
    method: "illinois" (default) or "bisection"; zeno_min_interval: two firings of one indicator
    closer than this are chattering (0 means ten times tol_time); coupling: the continuous
    coupling between events.
    """

    tol_time: float = 1e-9
    tol_value: float = 1e-9
    max_iter: int = 100
    max_microsteps: int = 10
    record_internal_steps: bool = False
    method: str = "illinois"
    zeno_min_interval: float = 0.0
    coupling: JacobiAlgorithm = field(default_factory=GaussSeidelAlgorithm)
    name: str = "Hybrid"

    def validate(self) -> None:
        if self.method not in METHODS:
            raise ValueError(f"HybridAlgorithm.method must be one of {METHODS}, "
                             f"got {self.method!r}")
        if not (self.tol_time > 0 and self.tol_value >= 0 and self.max_iter >= 1
                and self.max_microsteps >= 1 and self.zeno_min_interval >= 0):
            raise ValueError("HybridAlgorithm: tol_time > 0, tol_value >= 0, max_iter >= 1, "
                             "max_microsteps >= 1 and zeno_min_interval >= 0 are required")
        self.coupling.validate()


def log_events(records: Sequence[EventRecord], t0: float, dt: float, method: str) -> None:
    """The run's event instants: bracket on the grid, localization cost, handled events."""
    if not logger.isEnabledFor(logging.INFO):
        return
    instants: dict[tuple[float, int], list[EventRecord]] = {}
    for record in records:
        instants.setdefault((record.t, record.micro), []).append(record)
    rule = "=" * 80
    for (t, micro), group in instants.items():
        names = ", ".join(f"{r.component}.{r.event}" for r in group)
        logger.info(rule)
        if micro == 0:
            k = math.floor((t - t0) / dt + 1e-9)
            left = t0 + k * dt
            if k > 0 and math.isclose(left, t, abs_tol=1e-12) and group[0].iterations > 0:
                left -= dt  # located on a grid point: the crossing was in the step before
            logger.info("Event crossing in [%.6f, %.6f]: %s", left, left + dt, names)
            logger.debug("%s localization: %d iterations, %d rollbacks, %d doStep calls",
                         method, group[0].iterations, group[0].rollbacks, group[0].do_steps)
            logger.info("Event located at t=%.8f", t)
        logger.info("Handling %d event(s) at t=%.8f, micro=%d: %s", len(group), t, micro, names)
        logger.info(rule)
