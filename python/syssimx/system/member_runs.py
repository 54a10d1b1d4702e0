"""Members run by the engine on one System: the same system, parameter values per member.

A member on a reused System costs its initialize and run in Python (set_parameters, each
component's start, the run's checks and result): most of a 20-step member's CPU. When every
component is an FMUComponent the engine starts by itself (no Python hooks, indicators on
outputs, a declarative Reinitialize as its only handler, Real, Integer and Boolean start
values), the System is initialized once with the first member's values, and the engine runs
the members (ssx_run_member, one call each; ssx_run_members, one call for all, its samples
kept by the engine): each member's values written into the start values that initialize
wrote, the FMUs started again from them, the system initialized and run. The FMUs see the calls
a Python initialize and run make, in the same order: the histories are the same, bit for bit.
Other systems run the members through set_parameters, initialize and run.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from ..bridge.coupling_fallbacks import warn_coupling_fallbacks
from ..bridge.failure import raise_failure
from ..bridge.non_finite import warn_non_finite_outputs
from ..bridge.plan import engine_type
from ..components.fmu import FMUComponent
from ..core.port import PortType
from ..engine import ffi, lib
from ..errors import ConfigurationError, SysSimXWarning
from ..fmu.instance import start_values
from .recorded_events import RecordedEvents
from .results import HistoryView

if TYPE_CHECKING:
    from ..bridge.plan import EnginePlan


class System(Protocol):
    """What running members reads of a System (system.py imports this module)."""

    name: str
    components: dict[str, Any]
    _plan: EnginePlan | None
    is_initialized: bool


_NUMBER_TYPES = (PortType.REAL, PortType.INT, PortType.BOOL)


@dataclass
class MemberSamples:
    """One member's samples: the times, micro steps, "Component.port" -> values, and its
    events as (t, micro, "Component.event")."""

    time: np.ndarray
    micro: np.ndarray
    outputs: dict[str, np.ndarray] = field(default_factory=dict)
    events: tuple[tuple[float, int, str], ...] = ()


class MemberRuns:
    """The samples of members run one after another, stacked: member k's samples are the
    rows bounds[k] to bounds[k + 1] of `time`, `micro` and each column of `outputs`
    ("Component.port"); `events[k]` its events. A MemberSamples of one member (views) is
    made when asked for (runs[k])."""

    def __init__(self, time: np.ndarray, micro: np.ndarray, outputs: dict[str, np.ndarray],
                 bounds: np.ndarray, events: Sequence[tuple[tuple[float, int, str], ...]]
                 ) -> None:
        self.time, self.micro, self.outputs = time, micro, outputs
        self.bounds = bounds
        self.events = tuple(events)

    @classmethod
    def stacked(cls, members: Sequence[MemberSamples]) -> MemberRuns:
        """The members' samples, each copied into the stack."""
        bounds = np.zeros(len(members) + 1, dtype=np.int64)
        bounds[1:] = np.cumsum([len(member.time) for member in members])
        names = members[0].outputs if members else {}
        return cls(np.concatenate([member.time for member in members]) if members
                   else np.empty(0),
                   np.concatenate([member.micro for member in members]) if members
                   else np.empty(0, dtype=np.int64),
                   {name: np.concatenate([member.outputs[name] for member in members])
                    for name in names},
                   bounds, [member.events for member in members])

    def __len__(self) -> int:
        return len(self.bounds) - 1

    def __getitem__(self, k: int) -> MemberSamples:
        if not -len(self) <= k < len(self):
            raise IndexError(f"member {k} of {len(self)}")
        k %= len(self)
        rows = slice(int(self.bounds[k]), int(self.bounds[k + 1]))
        return MemberSamples(self.time[rows], self.micro[rows],
                             {name: column[rows] for name, column in self.outputs.items()},
                             self.events[k])

    def __iter__(self) -> Iterator[MemberSamples]:
        return (self[k] for k in range(len(self)))

    def last(self, name: str) -> np.ndarray:
        """Each member's last sample of the column `name`."""
        return self.outputs[name][self.bounds[1:] - 1]


def split_member_names(system: System, names: Sequence[str]) -> list[tuple[str, str]]:
    """("Component", "parameter") of each "Component.parameter" name of `system`."""
    split = []
    for name in names:
        component, _, variable = name.partition(".")
        if component not in system.components or not variable:
            raise ConfigurationError(f"{system.name}: {name!r} names no parameter of a "
                                     f"component; components: {sorted(system.components)}")
        split.append((component, variable))
    return split


def engine_runs_members(system: System, names: Sequence[tuple[str, str]]) -> bool:
    """Whether the engine can run members of `system` writing the parameters `names` (each
    component of the class FMUComponent itself, no Python hook, its indicators on outputs,
    no String parameter, the names Real, Integer or Boolean parameters)."""
    for component in system.components.values():
        if type(component) is not FMUComponent or component._python_hooks(engine_steps=True) \
                or component._has_text_parameters \
                or any(indicator.variable is None
                       for indicator in component.event_indicators.values()):
            return False
    for component_name, variable in names:
        component = system.components[component_name]
        parameter = component.info.parameters.get(variable) \
            if isinstance(component, FMUComponent) else None
        if parameter is None or parameter.type not in _NUMBER_TYPES:
            return False
    return True


class EngineMembers:
    """The members of an initialized System the engine runs (engine_runs_members said so):
    prepared once from the start values its last initialize wrote, which hold the parameters
    `names` (the System's components set them)."""

    def __init__(self, system: System, names: Sequence[tuple[str, str]]) -> None:
        plan = system._plan
        if plan is None or not system.is_initialized:
            raise ConfigurationError(f"{system.name}: call initialize(t0) first")
        self.plan: EnginePlan = plan
        self.system = system
        components = [plan.index[c] for c, _ in names]
        kinds = [system.components[c].info.parameters[v].type  # type: ignore[attr-defined]
                 for c, v in names]
        references = [system.components[c].value_reference(v)  # type: ignore[attr-defined]
                      for c, v in names]
        restart = [int(_restart_start(system.components[c], v)) for c, v in names]
        raw = lib().ssx_members_new(plan.sys, len(names), ffi.new("int[]", components or [0]),
                                    ffi.new("int[]", [engine_type(k) for k in kinds] or [0]),
                                    ffi.new("unsigned int[]", references or [0]),
                                    ffi.new("int[]", restart or [0]))
        if raw == ffi.NULL:
            raise_failure(plan)
        self.members = ffi.gc(raw, lib().ssx_members_free)
        plan.restart()  # the inputs as each member's initialize finds them: their starts
        for component in system.components.values():
            assert isinstance(component, FMUComponent)
            starts = component._by_type(component._initialization_starts(system_exits=True))
            values, _arrays = start_values(starts)  # alive until the engine copied them
            tolerance = component._experiment_tolerance
            experiment = ffi.new("ssx_fmu_experiment *", {
                "tolerance_defined": tolerance is not None, "tolerance": tolerance or 0.0})
            plan.check(lib().ssx_members_set_start(self.members, plan.index[component.name],
                                                   experiment, values),
                       f"{component.name}: member start values")
        self.values = ffi.new("double[]", max(len(names), 1))
        self.width = len(names)

    def start(self, values: Sequence[float], t0: float, tf: float, dt: float) -> int:
        """One member with `values` (one per name): the engine's status (-1: it failed, the
        plan's failure says why; its samples so far are the history)."""
        self.values[0:self.width] = values
        plan = self.plan
        plan.non_finite_warned.clear()
        plan.coupling_warned.clear()
        status = int(lib().ssx_run_member(self.members, self.values, t0, tf, dt))
        warn_non_finite_outputs(plan)
        warn_coupling_fallbacks(plan)
        return status

    def run(self, values: Sequence[float], t0: float, tf: float, dt: float) -> MemberSamples:
        """One member with `values` (one per name), its samples copied out."""
        if self.start(values, t0, tf, dt) < 0:
            raise_failure(self.plan)
        return member_samples(self.plan)

    def run_all(self, table: np.ndarray, t0: float, tf: float, dt: float) -> MemberRuns:
        """Every member of `table` (members x names) in one engine call, their samples copied
        once at the end. For a plan whose outputs are all Real and which has no indicators
        (no event columns, no events): the rows are the engine's values as they are."""
        plan = self.plan
        plan.non_finite_warned.clear()
        plan.coupling_warned.clear()
        values = np.ascontiguousarray(table, dtype=np.float64)
        status = lib().ssx_run_members(self.members, len(values),
                                       ffi.from_buffer("double[]", values), t0, tf, dt)
        warn_non_finite_outputs(plan)
        warn_coupling_fallbacks(plan)
        if status < 0:
            raise_failure(plan)
        return self.kept()

    def kept(self) -> MemberRuns:
        """The samples of the members run_all finished, copied (all of them once it returns;
        those before the one a failure or Ctrl-C stopped otherwise)."""
        plan = self.plan
        rows_at, micro_at = ffi.new("double **"), ffi.new("int **")
        bounds_at, width_at = ffi.new("size_t **"), ffi.new("size_t *")
        count = int(lib().ssx_members_samples(self.members, rows_at, micro_at, bounds_at,
                                              width_at))
        width = int(width_at[0])
        bounds = np.frombuffer(ffi.buffer(bounds_at[0], (count + 1) * ffi.sizeof("size_t")),
                               dtype=np.uintp).astype(np.int64)
        n_rows = int(bounds[-1])
        rows = np.frombuffer(ffi.buffer(rows_at[0], n_rows * width * 8),
                             dtype=np.float64).reshape(n_rows, width).copy()
        micro = np.frombuffer(ffi.buffer(micro_at[0], n_rows * 4), dtype=np.int32)
        outputs, column = {}, 1
        for name, recorded in plan.recorded().items():
            for port in recorded.outputs:
                outputs[f"{name}.{port}"] = rows[:, column]
                column += 1
        return MemberRuns(rows[:, 0], micro.astype(np.int64), outputs, bounds,
                          [()] * count)


def runs_in_one_call(plan: EnginePlan) -> bool:
    """Whether EngineMembers.run_all gives what member_samples gives for each member: every
    recorded output Real, no indicator."""
    return not plan.indicators and all(recorded.real_only and not recorded.events
                                       for recorded in plan.recorded().values())



def member_samples(plan: EnginePlan) -> MemberSamples:
    """The history of the member just run on `plan`, copied: each component's columns as a
    run's result gives them (EVENT columns included), and its events."""
    arrays = plan.history()
    recorded = RecordedEvents(plan, int(lib().ssx_event_count(plan.sys)))
    view = HistoryView(plan, recorded, arrays)
    outputs = {}
    for name in view:
        _t, columns = view[name]
        outputs.update({f"{name}.{port}": np.array(series) for port, series in columns.items()})
    events = tuple((e.t, e.micro, f"{e.component}.{e.event}") for e in recorded.made())
    return MemberSamples(np.array(arrays.time()), np.array(arrays.micro(), dtype=np.int64),
                         outputs, events)


def _restart_start(component: Any, parameter: str) -> bool:
    """Whether the engine's restart of `component` writes `parameter` as a start value (not
    one of the restart's own terms)."""
    terms = component._engine_restart()
    return terms is not None and parameter not in terms


def set_member_parameters(system: System, names: Sequence[tuple[str, str]],
                          values: Sequence[float]) -> None:
    """The member's values as the components' parameters (on a reused System: initialize comes
    next, so no warning of parameters waiting for it)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SysSimXWarning)
        for (component, variable), value in zip(names, values, strict=True):
            system.components[component].set_parameters(
                **{variable: _typed(system, component, variable, float(value))})


def member_table(system: System, values: Mapping[str, Sequence[float]]
                 ) -> tuple[list[tuple[str, str]], np.ndarray]:
    """The parameters named and a members x parameters table of their values."""
    names = split_member_names(system, list(values))
    columns = [np.asarray(column, dtype=np.float64) for column in values.values()]
    lengths = {len(column) for column in columns}
    if len(lengths) > 1:
        raise ConfigurationError(f"{system.name}: run_members needs as many values of each "
                                 f"parameter, got {sorted(lengths)}")
    table = np.column_stack(columns) if columns else np.empty((0, 0))
    if not np.all(np.isfinite(table)):
        raise ConfigurationError(f"{system.name}: run_members needs finite values")
    return names, table


def engine_writes_exactly(system: System, names: Sequence[tuple[str, str]],
                          values: Sequence[Any]) -> bool:
    """Whether the engine writes each value as set_parameters would write it: a Real
    parameter's an int or float, an Integer's an int of its range, a Boolean's a bool, 0 or 1
    (set_parameters refuses the others, the engine would not)."""
    for (component, variable), value in zip(names, values, strict=True):
        kind = system.components[component].info.parameters[variable].type
        number = isinstance(value, int | float) and not isinstance(value, bool)
        if kind == PortType.REAL and not number:
            return False
        if kind == PortType.INT and not (number and isinstance(value, int)
                                         and -2**31 <= value < 2**31):
            return False
        if kind == PortType.BOOL and not (isinstance(value, bool) or (value in (0, 1)
                                          and isinstance(value, int))):
            return False
    return True


def exact_table(system: System, names: Sequence[tuple[str, str]], table: np.ndarray) -> bool:
    """engine_writes_exactly for every row of `table`, its Integer and Boolean columns given as
    set_member_parameters gives them (ints and bools where the floats are whole, 0 or 1)."""
    for j, (component, variable) in enumerate(names):
        kind = system.components[component].info.parameters[variable].type
        column = table[:, j]
        if kind == PortType.INT and not np.all((column == np.round(column))
                                               & (column >= -2**31) & (column < 2**31)):
            return False
        if kind == PortType.BOOL and not np.all((column == 0) | (column == 1)):
            return False
    return True


def _typed(system: System, component: str, variable: str, value: float) -> Any:
    """`value` as a number of the parameter's type (a table holds floats)."""
    parameter = getattr(system.components[component], "info", None)
    kind = parameter.parameters[variable].type \
        if parameter is not None and variable in parameter.parameters else PortType.REAL
    return int(value) if kind == PortType.INT and float(value).is_integer() \
        else bool(value) if kind == PortType.BOOL and value in (0, 1) else value
