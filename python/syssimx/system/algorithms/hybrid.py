"""The hybrid algorithm: event detection, localization by rollback, superdense handling.

The engine does the work in C; this module holds the options and writes the event log from
the engine's event records after a run.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from dataclasses import InitVar, dataclass, field
from typing import TYPE_CHECKING

from ...bridge.options import engine_refusal
from ...engine import defaults, enum_name, enum_values, lib
from ...errors import ConfigurationError
from .coupling import JacobiAlgorithm, default_coupling
from .signature import EngineDefaults

if TYPE_CHECKING:
    from ..event_record import EventRecord
    from ..recorded_events import RecordedEvents

logger = logging.getLogger("syssimx.hybrid")


def locator_methods() -> dict[str, int]:
    """The engine's localization methods by name: ssx_locator's SSX_ILLINOIS is "illinois"."""
    return enum_values("ssx_locator", "SSX_")


@dataclass
class HybridAlgorithm:
    """Options of the hybrid algorithm: events located by rollback, handled between steps.

    Every default is the engine's (``ssx_get_defaults``), and the engine judges the values.

    Parameters
    ----------
    tol_time : float
        Width in seconds of the final bracket around an event.
    tol_value : float
        An indicator whose absolute value is below this counts as zero.
    max_iter : int
        Localization iterations per event.
    max_microsteps : int
        Handling rounds at one instant (superdense time) before a ZenoError.
    record_internal_steps : bool
        Also record the localization trials in the history.
    method : str
        ``"illinois"`` (Illinois held within two iterations of bisection's count),
        ``"bisection"`` or ``"illinois_unguarded"`` (Illinois alone, for comparison).
    zeno_min_interval : float
        Two firings of one indicator closer than this are chattering (0: the engine's default
        rule, see ``ssx_set_hybrid_options``).
    coupling : JacobiAlgorithm or GaussSeidelAlgorithm
        The continuous coupling between events.
    name : str
        The algorithm's name in reports.
    sign_tolerance : float
        SysSimX's option (>= 0): SysSimX treats an indicator below it as zero so that values
        resting near zero do not fire again. The engine tracks each indicator's side, so a
        handled crossing fires again only on a real crossing: no effect here.
    max_deferrals : int
        SysSimX's option (>= 0): SysSimX holds back a located event that its accepted
        trajectory has not reached yet. The engine locates on the accepted trajectory itself,
        so no event is ever premature: no effect here.
    raise_on_missed_event : bool
        SysSimX's option: SysSimX warns, or raises when true, when its accepted trajectory
        crosses where its trial did not. The two are the same trajectory here, so
        ``missed_events`` stays empty.
    gauss_seidel_algorithm : JacobiAlgorithm or GaussSeidelAlgorithm, optional
        SysSimX's name of ``coupling`` (also an attribute).
    """

    tol_time: float = field(default_factory=lambda: defaults().tol_time)
    tol_value: float = field(default_factory=lambda: defaults().tol_value)
    max_iter: int = field(default_factory=lambda: defaults().max_iterations)
    max_microsteps: int = field(default_factory=lambda: defaults().max_microsteps)
    record_internal_steps: bool = False
    method: str = field(default_factory=lambda: enum_name("ssx_locator", "SSX_",
                                                          defaults().locator))
    zeno_min_interval: float = field(default_factory=lambda: defaults().zeno_min_interval)
    coupling: JacobiAlgorithm = field(default_factory=default_coupling)
    name: str = "Hybrid"
    sign_tolerance: float = 1e-10
    max_deferrals: int = 50
    raise_on_missed_event: bool = False
    gauss_seidel_algorithm: InitVar[JacobiAlgorithm | None] = None
    missed_events: list = field(init=False, default_factory=list, repr=False)
    __signature__ = EngineDefaults()

    def __post_init__(self, gauss_seidel_algorithm: JacobiAlgorithm | None) -> None:
        if gauss_seidel_algorithm is not None:
            self.coupling = gauss_seidel_algorithm

    def locator(self) -> int:
        """The ssx_locator of `method` (checked by validate)."""
        return locator_methods()[self.method]

    def validate(self) -> None:
        methods = tuple(locator_methods())
        if self.method not in methods:
            raise ConfigurationError(f"HybridAlgorithm.method must be one of {methods}, "
                             f"got {self.method!r}")
        refusal = engine_refusal(lambda system: lib().ssx_set_hybrid_options(
            system, self.tol_time, self.tol_value, self.max_iter, self.max_microsteps,
            int(self.record_internal_steps), self.locator(), self.zeno_min_interval))
        if refusal is not None:
            raise ConfigurationError(
                f"HybridAlgorithm: the engine refuses tol_time={self.tol_time}, "
                             f"tol_value={self.tol_value}, max_iter={self.max_iter}, "
                             f"max_microsteps={self.max_microsteps}, zeno_min_interval="
                             f"{self.zeno_min_interval}: {refusal}")
        if not (math.isfinite(self.sign_tolerance) and self.sign_tolerance >= 0):
            raise ConfigurationError(
                f"HybridAlgorithm: sign_tolerance must be a finite number >= 0, "
                             f"got {self.sign_tolerance}")
        if isinstance(self.max_deferrals, bool) or not isinstance(self.max_deferrals, int) \
                or self.max_deferrals < 0:
            raise ConfigurationError(f"HybridAlgorithm: max_deferrals must be an integer >= 0, got "
                             f"{self.max_deferrals!r}")
        if not isinstance(self.coupling, JacobiAlgorithm):
            raise ConfigurationError(
                f"HybridAlgorithm: the coupling (gauss_seidel_algorithm) must be a "
                             f"JacobiAlgorithm or GaussSeidelAlgorithm, got {self.coupling!r}")
        self.coupling.validate()


def _indicators_at(group: Sequence[EventRecord], side: str) -> dict[str, dict[str, float]]:
    """{component: {event: value}} at the left or right end of the initial bracket."""
    values: dict[str, dict[str, float]] = {}
    for r in group:
        values.setdefault(r.component, {})[r.event] = (r.value_left if side == "left"
                                                       else r.value_right)
    return values


def _log_localization(group: Sequence[EventRecord], method: str) -> None:
    """The seed's DEBUG lines: indicators at the initial bracket ends, the bracket each trial
    splits, the indicators at the located time."""
    first = group[0]
    logger.debug("Starting %s for event localization ...", method)
    logger.debug("Indicators at left  (t=%.8f): %s", first.t_left, _indicators_at(group, "left"))
    logger.debug("Indicators at right (t=%.8f): %s", first.t_right,
                 _indicators_at(group, "right"))
    a, b = first.t_left, first.t_right
    for k, trial in enumerate(first.trials, start=1):
        logger.debug("%s iteration %d: interval [%.8f, %.8f]", method.capitalize(), k, a, b)
        a, b = trial.a, trial.b
    for r in group:
        logger.debug("Indicator %s.%s = %.4e", r.component, r.event, r.located_value)


def log_events(records: RecordedEvents, t0: float, method: str) -> None:
    """The event instants of the run from t0: bracket, localization trials (DEBUG), handled
    events. The records are made only when INFO is on."""
    if not logger.isEnabledFor(logging.INFO):
        return
    instants: dict[tuple[float, int], list[EventRecord]] = {}
    for record in records.made():
        if record.t >= t0:
            instants.setdefault((record.t, record.micro), []).append(record)
    rule = "=" * 80
    for (t, micro), group in instants.items():
        names = ", ".join(f"{r.component}.{r.event}" for r in group)
        logger.info(rule)
        if micro == 0 and not math.isnan(group[0].t_left):
            logger.info("Event crossing in [%.6f, %.6f]: %s", group[0].t_left,
                        group[0].t_right, names)
            _log_localization(group, method)
            logger.debug("%s localization: %d iterations, %d rollbacks, %d doStep calls",
                         method, group[0].iterations, group[0].rollbacks, group[0].do_steps)
            logger.info("Event located at t=%.8f", t)
            logger.debug("  Events at located time: %s", names)
        elif micro == 0:
            # a crossing at the very start: no bracket, the instant is the grid point itself
            logger.info("Event crossing at t=%.6f: %s", t, names)
        logger.info("Handling %d event(s) at t=%.8f, micro=%d: %s", len(group), t, micro, names)
        logger.info(rule)


def _gauss_seidel_algorithm(algorithm: HybridAlgorithm) -> JacobiAlgorithm:
    return algorithm.coupling


def _set_gauss_seidel_algorithm(algorithm: HybridAlgorithm, coupling: JacobiAlgorithm) -> None:
    algorithm.coupling = coupling


# SysSimX's name of the coupling, readable and settable after construction (the dataclass
# keeps the constructor argument above; the attribute is installed once the class exists)
HybridAlgorithm.gauss_seidel_algorithm = property(  # type: ignore[assignment]
    _gauss_seidel_algorithm, _set_gauss_seidel_algorithm)
