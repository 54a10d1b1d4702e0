"""Results of a run: the recorded samples, the events and the run's statistics."""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from ..bridge.history_arrays import HistoryArrays
from ..bridge.plan import recorded_columns
from ..bridge.run_outcome import RunOutcome
from ..core.suggest import did_you_mean
from ..errors import ConfigurationError, UnknownNameError
from ..extras import require
from . import csv_export
from .event_log import EventLog
from .event_record import EventRecord
from .recorded_events import RecordedEvents, as_recorded
from .termination import Termination

if TYPE_CHECKING:
    from ..bridge.plan import EnginePlan


class RecordedSystem(Protocol):
    """What a result reads of the System that recorded it."""

    name: str
    algorithm: Any
    history: Any
    termination: Termination | None
    components: Mapping[str, Any]
    _plan: EnginePlan | None

    def _mode_switches(self) -> dict[str, tuple[Any, ...]]: ...


@dataclass(frozen=True)
class Statistics:
    """Counters of a run (since System.initialize), and whether a component ended it."""

    macro_steps: int
    do_step_calls: int
    state_saves: int
    state_restores: int
    events: int
    localization_iterations: int
    loop_iterations: int
    loop_solves: int
    iterations_per_event: tuple[int, ...]
    directional_derivatives: int  # fmi2GetDirectionalDerivative calls for loop Jacobians
    own_events: int = 0  # events components handled inside their own steps (no rollback)
    termination: Termination | None = None
    # error-controlled communication steps (StepControl); zero without it
    accepted_steps: int = 0
    rejected_steps: int = 0  # taken again, shorter, after a rollback
    smallest_step: float = 0.0
    largest_step: float = 0.0
    largest_error: float = 0.0  # the largest weighted coupling error of an accepted step
    mean_error: float = 0.0  # over the accepted steps
    steps_over_tolerance: int = 0  # accepted at min_step though over the tolerance
    # FMUs that refused an input derivative order / told non-finite output derivatives
    input_order_fallbacks: int = 0
    output_derivative_fallbacks: int = 0
    # driven inputs the coupling-error control cannot measure (String, Binary): not in its error
    unmeasured_inputs: int = 0

    def __str__(self) -> str:
        lines = [f"macro steps: {self.macro_steps}",
                 f"doStep calls: {self.do_step_calls}",
                 f"state saves: {self.state_saves}, restores: {self.state_restores}",
                 f"events: {self.events}, localization iterations: "
                 f"{self.localization_iterations} {list(self.iterations_per_event)}",
                 f"events handled by components themselves: {self.own_events}",
                 f"loop solves: {self.loop_solves}, iterations: {self.loop_iterations}, "
                 f"directional derivatives: {self.directional_derivatives}"]
        if self.accepted_steps:
            lines.append(f"step control: {self.accepted_steps} accepted, {self.rejected_steps} "
                         f"rejected, steps {self.smallest_step:.3g}..{self.largest_step:.3g}, "
                         f"errors mean {self.mean_error:.3g}, largest {self.largest_error:.3g}, "
                         f"{self.steps_over_tolerance} over the tolerance at min_step"
                         + (f", {self.unmeasured_inputs} input(s) not measured"
                            if self.unmeasured_inputs else ""))
        if self.input_order_fallbacks or self.output_derivative_fallbacks:
            lines.append(f"fallbacks: {self.input_order_fallbacks} FMU(s) at a lower input "
                         f"order, {self.output_derivative_fallbacks} with output derivatives "
                         "estimated")
        if self.termination is not None:
            lines.append(f"terminated: {self.termination}")
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        from .result_display import statistics_html

        return statistics_html(self)


class StatisticsReading:
    """The engine's counters as they were at one instant (an ssx_statistics of the caller's,
    which nothing changes later), made a Statistics only when asked for: a result that
    nobody asks for its statistics costs no Python for them."""

    def __init__(self, counters: Any, events: RecordedEvents | Sequence[EventRecord],
                 termination: Termination | None, owner: Any = None) -> None:
        self._counters = counters
        self._owner = owner  # holds the memory of `counters` when they are a struct inside it
        self._events = as_recorded(events)
        self.termination = termination

    def statistics(self) -> Statistics:
        raw, events, termination = self._counters, self._events.made(), self.termination
        return Statistics(int(raw.macro_steps), int(raw.do_step_calls), int(raw.state_saves),
                          int(raw.state_restores), int(raw.events),
                          int(raw.localization_iterations), int(raw.loop_iterations),
                          int(raw.loop_solves),
                          tuple(e.iterations for e in events if not e.own),
                          int(raw.directional_derivatives), int(raw.own_events), termination,
                          int(raw.accepted_steps), int(raw.rejected_steps),
                          float(raw.smallest_step), float(raw.largest_step),
                          float(raw.largest_error),
                          float(raw.error_sum) / raw.accepted_steps if raw.accepted_steps
                          else 0.0, int(raw.steps_over_tolerance),
                          int(raw.input_order_fallbacks), int(raw.output_derivative_fallbacks),
                          int(raw.unmeasured_inputs))


class HistoryView:
    """Per-component (t, {port: values}) of the samples recorded when it was made: read-only
    numpy arrays over the engine's buffers, valid and unchanged for as long as they live (the
    engine records later samples elsewhere). A component's arrays are made when first asked
    for, so a run's result costs nothing per component; the view holds neither the plan nor
    the components (it outlives them)."""

    def __init__(self, plan: EnginePlan, events: RecordedEvents | Sequence[EventRecord],
                 arrays: HistoryArrays | None = None) -> None:
        """`arrays`: the samples to view (a run's outcome), else those recorded now."""
        self._recorded = plan.recorded()
        self._events = as_recorded(events)
        self._arrays = arrays if arrays is not None else plan.history()
        self._micro: np.ndarray | None = None  # made when first asked for
        self._data: dict[str, tuple[np.ndarray, dict[str, np.ndarray]]] = {}

    def _event_column(self, t: np.ndarray, component: str, event: str) -> np.ndarray:
        """EVENT output: True on the sample taken right after the event was handled."""
        column = np.zeros(len(t), dtype=bool)
        # samples are in time order but for the restarts a restored state makes
        # (System.restore_state): look in each ordered stretch only at those taken at the
        # event's instant
        starts = [0, *(np.flatnonzero(t[1:] < t[:-1]) + 1).tolist()]
        stretches = list(zip(starts, [*starts[1:], len(t)], strict=True))
        for e in self._events.made():
            if (e.component, e.event) == (component, event):
                for start, stop in stretches:
                    first = start + int(np.searchsorted(t[start:stop], e.t, "left"))
                    end = start + int(np.searchsorted(t[start:stop], e.t, "right"))
                    column[first:end] |= self.micro[first:end] == e.micro + 1
        return column

    @property
    def micro(self) -> np.ndarray:
        if self._micro is None:
            self._micro = self._arrays.micro()
        return self._micro

    def __getitem__(self, component: str) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        data = self._data.get(component)
        if data is not None:
            return data
        recorded = self._recorded.get(component)
        if recorded is None:
            raise UnknownNameError(f"no component {component!r}"
                                   f"{did_you_mean(component, self._recorded)}; components: "
                                   f"{sorted(self._recorded)}")
        t, values = recorded_columns(recorded, self._arrays)
        for event in recorded.events:
            values[event] = self._event_column(t, component, event)
        data = self._data[component] = (t, values)
        return data

    def __iter__(self) -> Iterator[str]:
        return iter(self._recorded)


class RecordedUnits(Mapping[str, dict[str, str | None]]):
    """{component: {port: unit or None}} of every recorded port (outputs and event columns)."""

    def __init__(self, plan: EnginePlan) -> None:
        self._recorded = plan.recorded()

    def __getitem__(self, name: str) -> dict[str, str | None]:
        return self._recorded[name].units

    def __iter__(self) -> Iterator[str]:
        return iter(self._recorded)

    def __len__(self) -> int:
        return len(self._recorded)


def recorded_units(plan: EnginePlan) -> RecordedUnits:
    """{component: {port: unit or None}} of every recorded port (outputs and event columns)."""
    return RecordedUnits(plan)


class SimulationResult:
    """`result["Comp"]` -> (t, {port: ndarray}); `.events`, `.statistics`, tables and plots.
    `.termination` is None, or which component asked to stop and when (the samples then end at
    the last communication point the whole system completed). `system_name`, `algorithm` (the
    algorithm's class name), `histories` ({component: (t, {port: values})}) and `units`
    ({component: {port: unit or None}}) are SysSimX's."""

    def __init__(self, system_name: str, algorithm: str, history: HistoryView,
                 events: RecordedEvents | Sequence[EventRecord],
                 statistics: Statistics | StatisticsReading,
                 units: Mapping[str, dict[str, str | None]], t0: float, tf: float, dt: float,
                 wall_time: float, mode_switches: dict[str, tuple[Any, ...]] | None = None
                 ) -> None:
        self.system_name = system_name
        self.algorithm = algorithm
        self._history = history
        self._events: RecordedEvents | EventLog = as_recorded(events)
        # {component: (ModeSwitchEvent, ...)} of the MultiComponents that switched
        self.mode_switches = mode_switches or {}
        self._statistics = statistics
        self.termination = statistics.termination
        self.units = units
        self.t0, self.tf, self.dt, self.wall_time = t0, tf, dt, wall_time

    @property
    def events(self) -> EventLog:
        """The run's events in handling order, made when first asked for."""
        if isinstance(self._events, RecordedEvents):
            self._events = EventLog(self._events.made())
        return self._events

    @events.setter
    def events(self, events: Sequence[EventRecord]) -> None:
        self._events = EventLog(events)

    @property
    def statistics(self) -> Statistics:
        """The run's counters (since System.initialize), read when the run returned."""
        if isinstance(self._statistics, StatisticsReading):
            self._statistics = self._statistics.statistics()
        return self._statistics

    @classmethod
    def from_system(cls, system: RecordedSystem, t0: float, tf: float, dt: float,
                    wall_time: float = math.nan, outcome: RunOutcome | None = None
                    ) -> SimulationResult:
        """The result of what `system` recorded since its initialize (also after a failed run);
        `outcome`: the engine's state as the run that just ended read it."""
        plan = system._plan
        if plan is None:
            raise ConfigurationError(f"{system.name}: nothing recorded yet; call initialize")
        if outcome is None:
            outcome = RunOutcome(plan)
        events = system.history.recorded_events
        return cls(system.name, type(system._run_algorithm(plan)).__name__,
                   HistoryView(plan, events, outcome.history),
                   events, StatisticsReading(outcome.statistics, events, system.termination,
                                             outcome.owner),
                   recorded_units(plan), t0, tf, dt, wall_time,
                   system._mode_switches())

    @property
    def component_names(self) -> list[str]:
        """The names of the components with recorded samples."""
        return list(self._history)

    @property
    def histories(self) -> dict[str, tuple[np.ndarray, dict[str, np.ndarray]]]:
        """Every component's samples, ``{name: (t, {port: values})}``."""
        return {name: self._history[name] for name in self._history}

    def __getitem__(self, component: str) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        return self._history[component]

    def __contains__(self, component: object) -> bool:
        return component in self.component_names

    def __repr__(self) -> str:
        return (f"SimulationResult({self.system_name!r}, t=[{self.t0}, {self.tf}], "
                f"dt={self.dt}, algorithm={self.algorithm}, components={self.component_names}, "
                f"events={len(self.events)})")

    @property
    def micro(self) -> np.ndarray:
        """Superdense index of each sample (events record a sample before and after)."""
        return self._history.micro

    def _repr_html_(self) -> str:
        from .result_display import result_html

        return result_html(self)

    def to_dataframe(self, component: str | None = None) -> Any:
        """SysSimX's tables (needs pandas). Without `component`: the tidy long table, columns
        component, port, time, micro, value, unit. With it: that component's wide table, time
        and micro columns and one column per port, `attrs["units"]` = {port: unit or None}.
        An event instant has two rows, the samples before (micro 0) and after handling
        (micro 1, and more for cascading events): (time, micro) identifies a row."""
        pd = require("pandas", "SimulationResult.to_dataframe")

        micro = self.micro
        if component is not None:
            t, ports = self[component]
            frame = pd.DataFrame({"time": t, "micro": micro, **ports})
            frame.attrs["units"] = dict(self.units[component])
            return frame
        frames = [pd.DataFrame({"component": name, "port": port, "time": t, "micro": micro,
                                "value": values, "unit": self.units[name][port]})
                  for name, (t, ports) in self.histories.items()
                  for port, values in ports.items()]
        if not frames:
            return pd.DataFrame(columns=list(csv_export.LONG_HEADER))
        return pd.concat(frames, ignore_index=True)

    def to_structured(self, component: str | None = None) -> np.ndarray:
        """FMPy's form of a result: a numpy structured array, field "time" first, then one
        field per port, named by the port for `component`, "Component.port" for every
        component without it. `fmpy.util.plot_result` and `write_csv` take it; an event
        instant has two rows, as in FMPy's results."""
        names = [component] if component is not None else self.component_names
        t = self[names[0]][0] if names else np.empty(0)
        fields: dict[str, np.ndarray] = {}
        for name in names:
            for port, values in self[name][1].items():
                fields[port if component is not None else f"{name}.{port}"] = values
        array = np.empty(len(t), dtype=[("time", np.float64),
                                        *((n, v.dtype) for n, v in fields.items())])
        array["time"] = t
        for field_name, values in fields.items():
            array[field_name] = values
        return array

    def to_csv(self, path: str | Path, component: str | None = None,
               units: bool = False, progress: csv_export.Progress | None = None) -> Path:
        """Write a CSV (no pandas needed): the tidy long table (component, port, time, micro,
        value, unit), or with `component` FMPy's CSV: time, then a column per port, headed
        "port [unit]" with `units`. `progress(rows)` is told the rows written as it goes.
        Returns the path."""
        if component is not None:
            t, ports = self[component]
            return csv_export.write_wide(path, t, ports, self.units[component] if units else None,
                                         progress)
        return csv_export.write_long(path, self.histories, self.units, self.micro, progress)

    def plot(self, signals: Sequence[str] | None = None, path: str | Path | None = None,
             **options: Any) -> Any:
        """Plot "<component>.<port>" signals (all when None); see syssimx.viz.plot."""
        from ..viz.plot import plot_result

        if signals is None:
            signals = [f"{c}.{p}" for c in self.component_names for p in self[c][1]]
        return plot_result(self, list(signals), path=path, **options)
