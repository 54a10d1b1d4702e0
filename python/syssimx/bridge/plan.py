"""EnginePlan: a System compiled into an engine system, and the Python side of its callbacks.

The plan knows no component class: each component kind adds itself (its `_add_to_plan` calls
add_python_component, add_fmu_component or add_table), so components/ and system/ both build
on this module and never on each other. The plan owns the ssx_system (freed when the plan is
collected, before the FMUs it borrows), knows each component's engine index and port order,
and owns the cffi callbacks: the engine calls none of them while the system is freed, so a
collected cycle of plan, callbacks and components may free them in any order. A Python
exception raised inside a callback is kept here and re-raised by the System.
"""

from __future__ import annotations

import functools
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.events import OWN_EVENTS
from ..core.port import TABLED_TYPES, PortType
from ..engine import enum_name, ffi, lib, string
from ..errors import ConfigurationError, SimulationTimeoutError
from ..plan.fmu_records import FMULoad, ScheduledClock, write_fmu, write_scheduled
from ..plan.records import Doubles, PlanRecords, Word, value_type_word
from .built_system import build_system
from .history_arrays import HistoryArrays

# A component of syssimx.components (Component or a subclass); typed loosely because
# the components build on this module.
Component = Any

# The hooks a component may run in Python (fields of ssx_hooks), in the order they are set.
HOOKS = ("do_step", "evaluate_outputs", "snapshot", "restore", "handle_events", "record")


# The FMUs a system borrows, by system address, until the system is freed. Held here rather
# than by the plan, because a garbage-collection cycle may clear the plan's attributes (and
# unload an FMU) before the system's destructor runs. FMUs refer to nothing of the plan.
_BORROWED_FMUS: dict[int, list[Any]] = {}


def _address(pointer: Any) -> int:
    return int(ffi.cast("uintptr_t", pointer))


def _free_system(release: Callable[[Any], None], address: int, pointer: Any) -> None:
    release(pointer)
    _BORROWED_FMUS.pop(address, None)


def engine_type(kind: PortType) -> int:
    """The ssx_value_type of a port type (the header's SSX_REAL, SSX_INTEGER, SSX_BOOLEAN)."""
    return int(getattr(lib(), _ENGINE_TYPE_NAMES[kind]))


_ENGINE_TYPE_NAMES = {PortType.REAL: "SSX_REAL", PortType.INT: "SSX_INTEGER",
                      PortType.BOOL: "SSX_BOOLEAN", PortType.STRING: "SSX_STRING",
                      PortType.BINARY: "SSX_BINARY"}


@dataclass(frozen=True)
class Binding:
    """Where a component lives in an engine system: the plan and its component index."""

    plan: EnginePlan
    index: int


@dataclass
class CallbackFailure:
    """A Python exception raised in a callback from the engine."""

    component: str
    where: str
    time: float
    error: BaseException


def bind(component: Component, binding: Binding | None) -> None:
    """Set where a component lives; a plan the component leaves remembers it (its System then
    refuses to run before initializing again)."""
    old = component._binding
    if old is not None and (binding is None or old.plan is not binding.plan) \
            and old.plan.left is None:
        old.plan.left = component.name
    component._binding = binding


def clock_names(component: Any, kind: str) -> list[str]:
    """A component's FMI 3.0 clocks of `kind` ("output_clocks" or "triggered_clocks"), in the
    engine's order; none for a component without clocks."""
    return list(getattr(component, kind, ()))


# the own events that name a clock: the ssx_own_event_kind word, the component's clock list
_CLOCKED_OWN_EVENTS = {"output_clock": "output_clocks", "clock_tick": "triggered_clocks"}


def _own_event_name(clocks: list[dict[str, list[str]]], component: int, own: int,
                    clock: int) -> str:
    """The name of a component's own event record: the clock's for an output clock's tick
    and a triggered clock's tick, else its kind's ("fmu_event", "clock_tick", ...); clocks:
    each component's clock names by kind word."""
    kind = enum_name("ssx_own_event_kind", "SSX_OWN_", own)
    names = clocks[component].get(kind)
    return names[clock - 1] if clock > 0 and names else kind


class EnginePlan:
    """The engine system of one System; rebuilt by System.initialize when the System's
    structure changed, else started again (`restart`)."""

    def __init__(self, name: str, components: Mapping[str, Component]) -> None:
        # the plan's records; `build` makes the engine system from them
        self.records = PlanRecords()
        self.records.add("system", name, about=name)
        self.sys: Any = None
        self._borrowed_fmus: list[Any] = []
        self._given: list[Any] = [ffi.NULL] * len(components)  # the FMUs Python loaded
        # what is attached once the system is built: hooks, indicator functions
        self._attach: list[Callable[[], None]] = []
        # What destructors call is looked up now: a collection may run them while cffi holds
        # the lock that a first lookup of a library function would wait for.
        self.release_history = lib().ssx_history_release
        self._callbacks: list[Any] = []  # kept alive as long as the engine may call them
        self.name = name
        self.deadline: float | None = None  # time.monotonic() at which the run times out
        self.timeout: float | None = None
        # the run's progress reporter (called with the time at each monitor call), if asked for
        self.progress: Callable[[float], None] | None = None
        self.components = dict(components)
        self.index = {name: i for i, name in enumerate(components)}
        self.outputs = {n: c.engine_outputs() for n, c in components.items()}
        self.inputs = {n: c.engine_inputs() for n, c in components.items()}
        self.driven: set[tuple[str, str]] = set()  # (component, input) of the connections
        self.indicators: list[tuple[str, str]] = []  # engine index -> (component, event)
        self.indicator_index: dict[tuple[str, str], int] = {}
        # engine number of an output clock source -> (component, clock)
        self.clock_sources: list[tuple[str, str]] = []
        # the name of a component's own event record (see _own_event_name); it holds the
        # components' clock names, not the plan, so event records keep no plan alive
        self.own_event_name = functools.partial(_own_event_name, [
            {kind: clock_names(c, clocks) for kind, clocks in _CLOCKED_OWN_EVENTS.items()}
            for c in components.values()])
        self.failure: CallbackFailure | None = None
        # (component, output) of the outputs warned of as non-finite since the last initialize
        self.non_finite_warned: set[tuple[int, int]] = set()
        # (component or -1, what) of the coupling's fallbacks warned of since (coupling_fallbacks)
        self.coupling_warned: set[tuple[int, str]] = set()
        # the first component that was bound elsewhere since (initialized in another System)
        self.left: str | None = None
        # parameters set on running FMUs (component -> names): they apply only at the next
        # initialize, so the next run warns of them once
        self.waiting_parameters: dict[str, tuple[str, ...]] = {}
        # the System's time after its last run; components read it (their `t`) when they have
        # not set a time of their own since that run (see CoSimComponent.t)
        self.time = 0.0
        self.runs = 0
        # components that may switch models (MultiComponent): what a result asks for switches
        self.switching = [n for n, c in components.items() if hasattr(c, "switch_events")]
        self.options: tuple[Any, ...] | None = None  # the algorithm's options the engine holds
        # what System.initialize set last (allow_non_finite, output_interval) and run's
        # output interval in grid steps: the engine keeps them, so equal ones are not set again
        self.initialize_settings: tuple[int, int | None] | None = None
        self.run_output_interval: int | None = None
        self._recorded: dict[str, RecordedComponent] | None = None
        self._do_step = lib().ssx_component_do_step
        self.tables: list[str] = []  # the table sources (add_table), in component order
        # what keeps the engine's port addresses (set again when ssx_initialize moves them)
        self._port_holders: list[_HookBuilder] = []
        for component in components.values():
            component._add_to_plan(self)

    def build(self, *more: PlanRecords) -> None:
        """The engine system of the records followed by `more` (the algorithm's), given the
        FMUs Python loaded; then the monitor, the Python hooks and the indicator functions
        attached to it. Refused, the components are bound to no plan."""
        try:
            raw = build_system(self.records.extended(*more), self._given)
        except BaseException:
            for component in self.components.values():
                if component._binding is not None and component._binding.plan is self:
                    component._binding = None
            raise
        address = _address(raw)
        _BORROWED_FMUS[address] = self._borrowed_fmus
        self.sys = ffi.gc(raw, functools.partial(_free_system, lib().ssx_system_free, address))
        self._watch()
        for attach in self._attach:
            attach()
        self._attach.clear()

    def initialize(self, t0: float) -> int:
        """ssx_initialize at t0 (its status); the port values may have moved into the engine's
        block in schedule order, so what keeps their addresses takes them again."""
        self.non_finite_warned.clear()
        self.coupling_warned.clear()
        status = int(lib().ssx_initialize(self.sys, t0))
        for holder in self._port_holders:
            holder.take_port_addresses()
        return status

    def restart(self) -> None:
        """Before the System initializes again on this plan: every input holds its start value
        (read now, as when the plan was built), no failure is pending."""
        starts = [c.input_start(port) for name, c in self.components.items()
                  for port in self.inputs[name]]
        self.check(lib().ssx_reset_inputs(self.sys, ffi.new("double[]", starts), len(starts)),
                   f"{self.name}: input start values")
        self.failure = None
        self.waiting_parameters.clear()

    def ran(self, t: float) -> None:
        """A run ended at t: every component's time is t until it sets its own."""
        self.time = t
        self.runs += 1

    # ------------------------------------------------------------------ callbacks
    def callback(self, signature: str, body: Callable[..., int], error: int,
                 on_escape: Callable[[BaseException], None]) -> Any:
        """A cffi callback owned by the plan. An exception escaping `body` (a Ctrl-C can arrive
        on its first line, before any try) is handed to `on_escape`, and C gets `error`."""
        def escaped(_type: Any, exc: BaseException | None, _traceback: Any) -> None:
            if exc is not None:
                on_escape(exc)

        callback = ffi.callback(signature, body, error=error, onerror=escaped)
        self._callbacks.append(callback)
        return callback

    def _watch(self) -> None:
        """The engine's monitor: Python's signal handlers run in it (Ctrl-C stops the run with
        KeyboardInterrupt), and it stops a run that passes its deadline."""
        engine_time = lib().ssx_time

        def stop(exc: BaseException) -> None:
            if self.failure is None:
                self.failure = CallbackFailure(self.name, "monitor",
                                               float(engine_time(self.sys)), exc)

        def monitor(_user: Any, t: float) -> int:
            if self.deadline is not None and time.monotonic() >= self.deadline:
                raise SimulationTimeoutError(
                    f"system {self.name!r}: the run exceeded timeout={self.timeout} s of wall "
                    f"time and stopped at t={t:.12g}; the samples up to there are in "
                    "get_history()", time=t)
            if self.progress is not None:
                self.progress(t)
            return 0

        lib().ssx_set_monitor(self.sys, self.callback("int(void *, double)", monitor, 1, stop),
                              ffi.NULL)

    # ------------------------------------------------------------------ building
    def check(self, result: int, what: str) -> int:
        if result < 0:
            message = ffi.string(lib().ssx_last_error(self.sys).message).decode(errors="replace")
            raise ConfigurationError(f"{what}: {message}")
        return result

    def add_python_component(self, component: Component, hooks: set[str]) -> None:
        """A component stepped by Python: the engine calls its `hooks` (do_step and
        evaluate_outputs at least) and keeps its port values in step with its ports."""
        self.records.add("python", component.name, component.can_rollback(),
                         about=component.name)
        self._add_ports(component, None)
        self._bind(component, hooks, is_fmu=False)

    def add_fmu_component(self, component: Component, fmu: Any, load: FMULoad,
                          can_get_set_state: bool, provides_directional_derivative: bool,
                          value_reference: Callable[[str], int], hooks: set[str],
                          model_exchange: tuple[int, int] | None = None, *,
                          calling_thread_only: bool = False,
                          interpolation: tuple[bool, int] = (False, 0)) -> None:
        """An FMU the engine steps itself; `hooks` lists what the component's Python
        overrides (none for a plain FMUComponent). `model_exchange`: the engine integrates it,
        with (continuous states, event indicators), at the tolerance the instance is set up
        with. `calling_thread_only` keeps its steps on the thread that runs the system.
        `interpolation`: (canInterpolateInputs, maxOutputDerivativeOrder) as the engine may use
        them. `load`: how the FMU was loaded, which a plan built without Python repeats. The
        system borrows the loaded FMU."""
        name, index = component.name, self.index[component.name]
        self._borrowed_fmus.append(fmu)
        self._given[index] = fmu
        write_fmu(self.records, index, name, can_get_set_state, model_exchange,
                  load)
        self.records.add("directional_derivatives", index, provides_directional_derivative,
                         about=f"{name}: directional derivatives")
        self.records.add("interpolation", index, interpolation[0], interpolation[1],
                         about=f"{name}: interpolation")
        if calling_thread_only:
            self.records.add("calling_thread_only", index, True,
                             about=f"{name}: calling thread only")
        self._add_ports(component, value_reference)
        self._bind(component, hooks, is_fmu=True)

    def add_scheduled_component(self, component: Component, fmu: Any, load: FMULoad,
                                value_reference: Callable[[str], int],
                                clocks: Sequence[ScheduledClock]) -> None:
        """An FMI 3.0 Scheduled Execution FMU the engine runs by activating its partitions:
        its clocks in the engine's order (the FMU's input clocks, then its output clocks). The
        system borrows the loaded FMU."""
        name, index = component.name, self.index[component.name]
        self._borrowed_fmus.append(fmu)
        self._given[index] = fmu
        write_scheduled(self.records, index, name, load)
        self._add_ports(component, value_reference)
        for clock in clocks:
            self.records.add("scheduled_clock", index, clock.kind, clock.value_reference,
                             clock.priority, clock.interval, clock.shift, clock.interval_tunable,
                             Doubles(np.asarray(clock.times, dtype=np.float64)),
                             about=f"{name}: clock {clock.value_reference}")
        outputs = self.outputs[name]
        for k, clock in enumerate(clocks):
            for port in clock.moves:
                self.records.add("scheduled_clock_output", index, k, outputs.index(port),
                                 about=f"{name}.{port}")
        self._bind(component, set(), is_fmu=True)

    def _add_ports(self, component: Component, vr: Callable[[str], int] | None) -> None:
        name, index = component.name, self.index[component.name]
        for port in self.outputs[name]:
            spec = component.output_specs[port]
            self.records.add("output", index, value_type_word(spec.type), vr(port) if vr else 0,
                             about=f"{name}.{port}")
        for port in self.inputs[name]:
            spec = component.input_specs[port]
            start = component.input_start(port)
            # a String input's text, a Binary one's bytes, else a number
            self.records.add("input", index, value_type_word(spec.type), vr(port) if vr else 0,
                             start if isinstance(start, str | bytes) else float(start),
                             about=f"{name}.{port}")

    def _bind(self, component: Component, hooks: set[str], is_fmu: bool) -> None:
        index = self.index[component.name]
        bind(component, Binding(self, index))
        if hooks and is_fmu:  # a placeholder: the hooks are Python's to attach
            self.records.add("hooks", index, about=f"{component.name}: hooks")

        def attach_hooks() -> None:
            builder = _HookBuilder(self, component, is_fmu)
            struct = builder.build(hooks)
            if "do_step" in hooks and not is_fmu:  # the one hook that keeps the addresses
                self._port_holders.append(builder)
            if struct is not None:  # the engine copies the struct; the callbacks are kept
                self.check(lib().ssx_set_hooks(self.sys, index, struct),
                           f"{component.name}: hooks")
        self._attach.append(attach_hooks)

    def set_restart(self, component: Component, tolerance: float | None, starts: Any,
                    targets: list[int], sources: list[int], gains: list[float]) -> None:
        """The component's events are handled by the engine (ssx_set_restart_handler): a
        restart with `starts` (an ssx_fmu_values, copied by the engine) and each Real target =
        gain * its source output."""
        experiment = ffi.new("ssx_fmu_experiment *", {
            "tolerance_defined": tolerance is not None, "tolerance": tolerance or 0.0})
        n = len(targets)
        self.check(lib().ssx_set_restart_handler(
            self.sys, self.index[component.name], experiment, starts,
            ffi.new("unsigned int[]", targets), ffi.new("int[]", sources),
            ffi.new("double[]", gains), ffi.new("double[]", n), n),
            f"{component.name}: event handler")

    def add_table(self, component: Component, time: np.ndarray,
                  columns: Mapping[str, np.ndarray], hold: set[str]) -> None:
        """A table source is evaluated in C: its table is copied into the engine, no hooks.
        columns: the values of each output (in the order of engine_outputs)."""
        name, index = component.name, self.index[component.name]
        self.records.add("table", name, Doubles(time), about=name)
        for port in self.outputs[name]:
            values = Doubles(columns[port])
            self.records.add("table_column", index,
                             value_type_word(component.output_specs[port].type), port in hold,
                             values, about=f"{name}.{port}")
        component._binding = Binding(self, index)
        self.tables.append(name)

    def start_table(self, table: Component, t0: float) -> dict[str, float]:
        """The table's outputs at t0 (the value on the left of a jump), written before any
        component initializes, so every component, whatever its place in the schedule, starts
        from them; returned by output name."""
        index = self.index[table.name]
        outputs = lib().ssx_outputs(self.sys, index)
        self.check(lib().ssx_table_values(self.sys, index, t0, 0, outputs), table.name)
        return {name: float(outputs[i]) for i, name in enumerate(self.outputs[table.name])}

    def connect(self, src: str, src_port: str, dst: str, dst_port: str, scale: float,
                offset: float) -> None:
        self.records.add("connect", self.index[src], self.outputs[src].index(src_port),
                         self.index[dst], self.inputs[dst].index(dst_port), float(scale),
                         float(offset), about=f"connection {src}.{src_port} -> {dst}.{dst_port}")
        self.driven.add((dst, dst_port))

    def add_indicator(self, component: Component, event: str) -> None:
        indicator = component.event_indicators[event]
        index = self.index[component.name]
        number, about = len(self.indicators), f"{component.name}.{event}"
        if indicator.variable is not None:
            output = self.outputs[component.name].index(indicator.variable)
            self.records.add("indicator_output", index, output, int(indicator.direction),
                             about=about)
            slope = getattr(component, "_indicator_slope", None)
            slope_vr = slope(indicator.variable) if slope is not None else None
            if slope_vr is not None:
                self.records.add("indicator_slope", number, slope_vr, about=about)
        else:
            self.records.add("indicator_callback", index, int(indicator.direction), about=about)

            def attach_function() -> None:
                engine_time = lib().ssx_time
                callback = self.callback(
                    "int(void *, double, double *)", self._indicator_callback(component, event),
                    -1, lambda exc: self.fail(component, f"event indicator {event!r}",
                                              float(engine_time(self.sys)), exc))
                self.check(lib().ssx_set_indicator_callback(self.sys, number, callback,
                                                            ffi.NULL), about)
            self._attach.append(attach_function)
        self.indicators.append((component.name, event))
        self.indicator_index[(component.name, event)] = number

    def _indicator_callback(self, component: Component, event: str
                            ) -> Callable[[Any, float, Any], int]:
        func = component.event_indicators[event].func
        assert func is not None

        def evaluate(_user: Any, t: float, value: Any) -> int:
            try:
                value[0] = float(func(component))
                return 0
            except BaseException as exc:  # kept and re-raised by System.run
                self.fail(component, f"event indicator {event!r}", t, exc)
                return -1
        return evaluate

    def add_event_connection(self, src: str, event: str, dst: str, own: bool = False,
                             dst_port: str | None = None) -> None:
        """dst listens to src's indicator or output clock `event`, or with `own` to src's own
        events; where dst_port is a triggered input clock of dst, the source ticks it."""
        if own:
            kind, index = Word("own_events"), self.index[src]
        elif event in clock_names(self.components[src], "output_clocks"):
            kind, index = Word("output_clock"), self._clock_source(src, event)
        else:
            kind, index = Word("indicator"), self.indicator_index[(src, event)]
        about = f"{src}.{event} -> {dst}" + (f".{dst_port}" if dst_port else "")
        triggered = clock_names(self.components[dst], "triggered_clocks")
        if dst_port in triggered:
            self.records.add("connect_clock", kind, index, self.index[dst],
                             triggered.index(dst_port), about=about)
        else:
            self.records.add("subscribe", kind, index, self.index[dst], about=about)

    def _clock_source(self, component: str, clock: str) -> int:
        """The engine's number of the output clock source `clock` of `component` (one per
        clock, numbered in the order they are first named)."""
        if (component, clock) not in self.clock_sources:
            outputs = clock_names(self.components[component], "output_clocks")
            self.records.add("output_clock_source", self.index[component],
                             outputs.index(clock), about=f"{component}.{clock}")
            self.clock_sources.append((component, clock))
        return self.clock_sources.index((component, clock))

    def fail(self, component: Component, where: str, t: float, exc: BaseException) -> None:
        if self.failure is None:
            self.failure = CallbackFailure(component.name, where, t, exc)

    # ------------------------------------------------------------------ port values
    def _array(self, component: Component, direction: str) -> Any:
        index = self.index[component.name]
        return (lib().ssx_outputs if direction == "out" else lib().ssx_inputs)(self.sys, index)

    def input_array(self, component: Component) -> Any:
        """The engine's input values of a component now (a C array, in the order of `inputs`;
        ssx_initialize may move it)."""
        return self._array(component, "in")

    def port_value(self, component: Component, direction: str, port: str) -> float:
        """The engine's value of a port (a String port's: its text's number, see text)."""
        names = self.outputs if direction == "out" else self.inputs
        return float(self._array(component, direction)[names[component.name].index(port)])

    def text_number(self, value: str | bytes) -> float:
        """The number of a text or of bytes in the system's table of values (String and
        Binary ports hold numbers)."""
        data = value.encode() if isinstance(value, str) else bytes(value)
        number = ffi.new("double *")
        self.check(lib().ssx_bytes_number(self.sys, data, len(data), number),
                   "a String or Binary value")
        return float(number[0])

    def text(self, number: float) -> str:
        """The text a String port's number stands for."""
        return string(lib().ssx_text(self.sys, number))

    def tabled_bytes(self, number: float) -> bytes:
        """The bytes a Binary port's number stands for."""
        size = ffi.new("size_t *")
        data = lib().ssx_bytes(self.sys, number, size)
        return b"" if data == ffi.NULL else ffi.buffer(data, size[0])[:]

    def to_engine(self, kind: PortType, value: Any) -> float:
        """A port value as the engine holds it."""
        return self.text_number(value) if kind in TABLED_TYPES else float(value)

    def from_engine(self, kind: PortType, value: float) -> Any:
        """An engine value as the value of a port of type `kind`."""
        return self.text(value) if kind == PortType.STRING else \
            self.tabled_bytes(value) if kind == PortType.BINARY else typed(kind, value)

    def write_inputs(self, component: Component,
                     values: Mapping[str, Any] | None = None) -> None:
        """Copy input values (the component's ports, or `values`) into the engine."""
        array = self._array(component, "in")
        for i, name in enumerate(self.inputs[component.name]):
            kind = component.input_specs[name].type
            if values is None:
                array[i] = self.to_engine(kind, component.inputs[name].raw())
            elif name in values:
                array[i] = self.to_engine(kind, component.input_specs[name].coerce(values[name]))

    def pull_inputs(self, component: Component) -> None:
        """Engine inputs -> the component's input ports (Python components)."""
        array = self._array(component, "in")
        for i, name in enumerate(self.inputs[component.name]):
            port = component.inputs[name]
            port._raw = self.from_engine(port.spec.type, array[i])

    def push_outputs(self, component: Component) -> None:
        """The component's output ports -> engine outputs (Python components)."""
        array = self._array(component, "out")
        for i, name in enumerate(self.outputs[component.name]):
            port = component.outputs[name]
            array[i] = self.to_engine(port.spec.type, port.raw())

    def read_outputs(self, component: Component) -> None:
        index = self.index[component.name]
        self.raise_for(lib().ssx_component_read_outputs(self.sys, index), component)

    def builtin_do_step(self, index: int, t: float, dt: float) -> None:
        """The engine's own doStep of component `index` (called per substep by overrides)."""
        if self._do_step(self.sys, index, t, dt) < 0:
            self.raise_for(-1, self.components[list(self.index)[index]])

    def raise_for(self, result: int, component: Component) -> None:
        if result < 0:
            from .failure import raise_failure

            raise_failure(self, default_component=component.name)

    # ------------------------------------------------------------------ history
    def history(self) -> HistoryArrays:
        """The samples recorded so far, as arrays that stay valid and unchanged for their life."""
        return HistoryArrays(self.sys, self.release_history, self.tabled_values())

    def tabled_values(self) -> tuple[bytes, ...]:
        """Every value of the system's String and Binary ports so far, by number."""
        return tuple(self.tabled_bytes(k) for k in range(lib().ssx_text_count(self.sys)))

    def component_history(self, component: Component, arrays: HistoryArrays | None = None
                          ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """(time, {output: values}) of one component, without a copy (Real outputs)."""
        return recorded_columns(self.recorded()[component.name],
                                arrays if arrays is not None else self.history())

    def recorded(self) -> dict[str, RecordedComponent]:
        """What each component records, found once per plan: results read it without the
        plan or its components (a result outlives both)."""
        if self._recorded is None:
            self._recorded = {}
            for name, c in self.components.items():
                outputs = tuple(self.outputs[name])
                events = tuple(c.event_indicators)
                types = tuple(c.output_specs[p].type for p in outputs)
                self._recorded[name] = RecordedComponent(
                    self.index[name], outputs, types, events,
                    {p: c.output_specs[p].unit for p in (*outputs, *events)},
                    all(kind == PortType.REAL for kind in types))
        return self._recorded


@dataclass(frozen=True)
class RecordedComponent:
    """Where a component's samples are and what they are: its engine index, its outputs with
    their types, its event columns, and the unit of each."""

    index: int
    outputs: tuple[str, ...]
    types: tuple[PortType, ...]
    events: tuple[str, ...]
    units: dict[str, str | None]
    real_only: bool  # every output Real: its columns are the matrix's, unconverted


def recorded_columns(recorded: RecordedComponent, arrays: HistoryArrays
                     ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """(time, {output: values}) of one component in `arrays`, without a copy (Real outputs;
    Integer and Boolean ones converted, String and Binary ones object arrays of their texts
    and bytes)."""
    matrix = arrays.values(recorded.index, len(recorded.outputs))
    if recorded.real_only:
        return arrays.time(), {name: matrix[:, j] for j, name in enumerate(recorded.outputs)}
    columns = {}
    for j, (name, kind) in enumerate(zip(recorded.outputs, recorded.types, strict=True)):
        column = matrix[:, j]
        columns[name] = (column.astype(np.int64) if kind == PortType.INT
                         else column != 0.0 if kind == PortType.BOOL
                         else arrays.tabled(column, kind) if kind in TABLED_TYPES else column)
    return arrays.time(), columns


def typed(kind: PortType, value: float) -> float | int | bool:
    return _FROM_ENGINE[kind](value)


def _is_true(value: float) -> bool:
    return value != 0.0


# an engine value (a double) as the value of a port of each type
_FROM_ENGINE: dict[PortType, Callable[[float], float | int | bool]] = {
    PortType.REAL: float, PortType.INT: round, PortType.BOOL: _is_true}


class _HookBuilder:
    """The ssx_hooks of one component: only the hooks its Python code needs."""

    def __init__(self, plan: EnginePlan, component: Component, is_fmu: bool) -> None:
        self.plan = plan
        self.component = component
        self.is_fmu = is_fmu  # the engine owns the ports and steps the FMU itself
        self.snapshots: dict[int, Any] = {}
        self.where: str | None = None  # a more precise place, set while a hook runs
        # what a Python component's step moves, found once: the engine's port arrays (taken
        # again after each initialize, which may move them) and, in engine order, the port
        # names with the conversion of an engine value to the port's type
        self.ports: tuple[Any, Any] = (ffi.NULL, ffi.NULL)
        self.take_port_addresses()
        self.input_names = [(name, functools.partial(plan.from_engine, kind)
                             if kind in TABLED_TYPES else _FROM_ENGINE[kind])
                            for name in plan.inputs[component.name]
                            for kind in (component.input_specs[name].type,)]
        self.output_names = [(i, name, plan.text_number if component.output_specs[name].type
                              in TABLED_TYPES else float)
                             for i, name in enumerate(plan.outputs[component.name])]

    def take_port_addresses(self) -> None:
        """The engine's (inputs, outputs) arrays of the component, where they are now."""
        index = self.plan.index[self.component.name]
        self.ports = (lib().ssx_inputs(self.plan.sys, index),
                      lib().ssx_outputs(self.plan.sys, index))

    def _guard(self, where: str, body: Callable[..., None], time_arg: int | None
               ) -> Callable[..., int]:
        """A callback running `body`; an exception is kept with the time (argument `time_arg`,
        or the engine's time) and reported as failure."""
        plan, component = self.plan, self.component

        def hook(_user: Any, *args: Any) -> int:
            try:
                body(*args)
                return 0
            except BaseException as exc:  # kept and re-raised by System.run
                t = args[time_arg] if time_arg is not None else lib().ssx_time(plan.sys)
                plan.fail(component, self.where or where, float(t), exc)
                return -1
            finally:
                self.where = None
        return hook

    def build(self, hooks: set[str]) -> Any:
        """The ssx_hooks with the callbacks of `hooks` (names of HOOKS), None for none."""
        if not hooks:
            return None
        c, plan = self.component, self.plan
        struct = ffi.new("ssx_hooks *")
        engine_time = lib().ssx_time
        callbacks = {
            "do_step": ("int(void *, double, double)", "do_step", self._do_step, 0),
            "evaluate_outputs": ("int(void *, double)", "evaluate_outputs",
                                 self._evaluate_outputs, -1),
            "snapshot": ("int(void *, int)", "snapshot_state", self._snapshot, None),
            "restore": ("int(void *, int, double)", "restore_state", self._restore, -1),
            "handle_events": ("int(void *, int *, int, double)", "event handler",
                              self._handle_events, -1),
            "record": ("int(void *, double)", "_record_outputs", c._record_outputs, -1),
        }
        for field in HOOKS:
            if field not in hooks:
                continue
            signature, where, body, time_arg = callbacks[field]
            guarded = self._python_step() if field == "do_step" and not self.is_fmu \
                else self._guard(where, body, time_arg)
            callback = plan.callback(
                signature, guarded, -1,
                lambda exc, where=where: plan.fail(c, self.where or where,
                                                   float(engine_time(plan.sys)), exc))
            setattr(struct[0], field, callback)
        return struct

    def _do_step(self, t: float, dt: float) -> None:
        """An FMU component's overridden step (the engine moves its ports)."""
        c = self.component
        c._do_step_internal(t, dt)
        c.t = t + dt
        c._update_output_states(t + dt)

    def _python_step(self) -> Callable[[Any, float, float], int]:
        """The do_step callback of a Python component, the one hook that runs every step:
        engine inputs into its input ports, its step, its output ports into the engine, with
        what it needs looked up once."""
        plan, c = self.plan, self.component
        input_names, output_names = list(enumerate(self.input_names)), self.output_names

        def step(_user: Any, t: float, dt: float) -> int:
            try:
                inputs, outputs = self.ports
                ports = c.inputs
                for i, (name, convert) in input_names:
                    ports[name]._raw = convert(inputs[i])
                c._do_step_internal(t, dt)
                c.t = t + dt
                c._update_output_states(t + dt)
                ports = c.outputs
                for i, name, convert in output_names:
                    outputs[i] = convert(ports[name].raw())
                return 0
            except BaseException as exc:  # kept and re-raised by System.run
                plan.fail(c, "do_step", t, exc)
                return -1
        return step

    def _evaluate_outputs(self, t: float) -> None:
        c = self.component
        self.plan.pull_inputs(c)
        values = c.evaluate_outputs({n: c.inputs[n].get() for n in self.plan.inputs[c.name]}, t)
        for name, value in values.items():
            if name in c.outputs and c.outputs[name].spec.type != PortType.EVENT:
                c.outputs[name].set(value, t)
        if self.is_fmu:
            self.plan.read_outputs(c)
        else:
            self.plan.push_outputs(c)

    def _snapshot(self, slot: int) -> None:
        c = self.component
        self._drop_snapshot(slot)
        ports = {n: p.raw() for n, p in c.outputs.items()}
        self.snapshots[slot] = (c.snapshot_state(), ports)

    def _restore(self, slot: int, t: float) -> None:
        c = self.component
        snapshot, ports = self.snapshots[slot]
        if not self.is_fmu:
            for name, value in ports.items():
                c.outputs[name]._raw = value
        c.restore_state(snapshot, t)
        c.t = t

    def _drop_snapshot(self, slot: int) -> None:
        entry = self.snapshots.pop(slot, None)
        if entry is not None and hasattr(entry[0], "free"):
            entry[0].free()

    def _handle_events(self, indicators: Any, n: int, t: float) -> None:
        c = self.component
        # an indicator by its index, a component's own events as -1 - component, an output
        # clock as -1 - n_components - its source number
        n_components = len(self.plan.index)
        names = list(dict.fromkeys(
            self.plan.indicators[indicators[i]][1] if indicators[i] >= 0
            else OWN_EVENTS if indicators[i] >= -n_components
            else self.plan.clock_sources[-1 - n_components - indicators[i]][1]
            for i in range(n)))
        if any(indicators[i] < 0 for i in range(n)):
            # t is the own event's time; the component stands at the communication point after
            c.t = float(lib().ssx_time(self.plan.sys))
        self.where = f"event handler for {', '.join(names)}"
        c._handle_events_internal(names, t)
        c._update_output_states(t, names)
        if not self.is_fmu:
            self.plan.push_outputs(c)
