"""System: components, connections and event connections, run by the engine."""

from __future__ import annotations

import dataclasses
import logging
import math
import numbers
import time
import warnings
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from .. import units
from ..bridge.coupling_fallbacks import warn_coupling_fallbacks
from ..bridge.failure import raise_failure
from ..bridge.non_finite import warn_non_finite_outputs
from ..bridge.observers import add_observer, remove_observer
from ..bridge.observers import keep_history as keep_history_samples
from ..bridge.plan import EnginePlan, clock_names
from ..bridge.run_outcome import RunOutcome
from ..components.base import CoSimComponent
from ..core.events import OWN_EVENTS
from ..core.port import PortType
from ..core.suggest import did_you_mean
from ..engine import defaults, ffi, lib
from ..errors import (
    ConfigurationError,
    RunInterrupted,
    RunTerminated,
    StateError,
    SysSimXWarning,
)
from ..graph.analysis import SystemAnalysis, analyze_system, check_undeclared_dependencies
from ..units import conversion
from .algorithms import Algorithm, HybridAlgorithm, JacobiAlgorithm, StepControl
from .algorithms.coupling import default_coupling, loop_jacobians
from .algorithms.hybrid import log_events
from .connection import Connection, EventConnection
from .member_runs import (
    EngineMembers,
    MemberRuns,
    engine_runs_members,
    exact_table,
    member_samples,
    member_table,
    runs_in_one_call,
    set_member_parameters,
)
from .plan_options import option_records, setting_records
from .plan_writing import coupling_of, plan_text, write_text
from .progress import ProgressCallback, run_progress
from .recorded_events import RecordedEvents
from .results import HistoryView, SimulationResult
from .run_signals import sigterm_stops_the_run
from .run_stream import RunStream
from .saved_state import SystemState, restore_state, save_state, state_from_bytes
from .system_history import SystemHistory
from .table_starts import start_tables
from .termination import Termination, read_termination

logger = logging.getLogger("syssimx.system")

_COMPATIBLE = {PortType.REAL: {PortType.REAL, PortType.INT, PortType.BOOL},
               PortType.INT: {PortType.INT, PortType.BOOL}, PortType.BOOL: {PortType.BOOL},
               PortType.STRING: {PortType.STRING}, PortType.BINARY: {PortType.BINARY}}


class System:
    """A co-simulated system. Build it, `initialize(t0)`, then `run(t0, tf, dt)`."""

    def __init__(self, name: str, *, undeclared_dependencies: str = "all") -> None:
        """undeclared_dependencies: what an FMU output whose dependencies its ModelStructure
        does not declare depends on: "all" inputs (the standard; a loop this makes is solved
        at every communication point) or "none" (the loop is coupled explicitly, as libcosim
        couples every connection)."""
        self.name = name
        self._undeclared_dependencies = check_undeclared_dependencies(undeclared_dependencies)
        self.components: dict[str, CoSimComponent] = {}
        self.connections: list[Connection] = []
        self._drivers: dict[tuple[str, str], Connection] = {}  # (component, input) -> its driver
        self.event_connections: list[EventConnection] = []
        self.history = SystemHistory(system=self)
        self.t = 0.0
        self.is_initialized = False
        self.termination: Termination | None = None  # set when a component ended the run
        self._algorithm: Algorithm = default_coupling()
        self._algorithm_chosen = False
        self._plan: EnginePlan | None = None
        self._observers: list[Any] = []  # System.add_observer, attached to every plan
        self._observer_ids: dict[int, int] = {}  # id(observer) -> its id in the current plan
        self._streamed: set[int] = set()  # writer objects that got their start point
        self._history_off = False  # a run with keep_history=False since initialize
        self._plan_structure: tuple[Any, ...] | None = None  # what _plan was compiled from

    def __repr__(self) -> str:
        return f"System({self.name!r}, components={list(self.components)})"

    @property
    def undeclared_dependencies(self) -> str:
        """What an output that declares no dependencies depends on, ``"all"`` or ``"none"``
        (see the constructor); a change takes effect at the next initialize."""
        return self._undeclared_dependencies

    @undeclared_dependencies.setter
    def undeclared_dependencies(self, value: str) -> None:
        self._undeclared_dependencies = check_undeclared_dependencies(value)
        self.is_initialized = False

    # ------------------------------------------------------------------ algorithm
    @property
    def algorithm(self) -> Algorithm:
        """The master algorithm the next initialize uses.

        The one set, else Gauss-Seidel; a system with event indicators gets a HybridAlgorithm
        around its coupling."""
        if not isinstance(self._algorithm, HybridAlgorithm) and self._has_indicators():
            chosen = self._algorithm if self._algorithm_chosen else default_coupling()
            assert isinstance(chosen, JacobiAlgorithm)
            self._algorithm = HybridAlgorithm(coupling=chosen)
            logger.debug("%s: event indicators present, using the hybrid algorithm", self.name)
        return self._algorithm

    @algorithm.setter
    def algorithm(self, algorithm: Algorithm) -> None:
        self.set_algorithm(algorithm)

    def set_algorithm(self, algorithm: Algorithm) -> None:
        """Use `algorithm` (a JacobiAlgorithm, GaussSeidelAlgorithm or HybridAlgorithm) from
        the next initialize on; its options are checked now."""
        if not isinstance(algorithm, JacobiAlgorithm | HybridAlgorithm):
            raise ConfigurationError(f"{self.name}: unknown algorithm {algorithm!r}; use "
                                     "JacobiAlgorithm, GaussSeidelAlgorithm or HybridAlgorithm")
        algorithm.validate()
        self._algorithm = algorithm
        self._algorithm_chosen = True

    def _has_indicators(self) -> bool:
        return any(c.event_indicators for c in self.components.values())

    # ------------------------------------------------------------------ building
    def add_component(self, component: CoSimComponent) -> None:
        """Add a component; its name must be unique in the system."""
        if not isinstance(component, CoSimComponent):
            raise ConfigurationError(f"{self.name}: {component!r} is not a CoSimComponent")
        if component.name in self.components:
            raise ConfigurationError(f"{self.name}: a component named {component.name!r} "
                                     "already exists")
        component._sync_ports()
        self.components[component.name] = component
        self.is_initialized = False

    def _component(self, name: str) -> CoSimComponent:
        if name not in self.components:
            raise ConfigurationError(f"{self.name}: unknown component {name!r}"
                                     f"{did_you_mean(name, self.components)}; components: "
                                     f"{sorted(self.components) or 'none'}")
        return self.components[name]

    def add_connection(self, connection: Connection) -> None:
        """Check names, types and units now; one driver per input. Reads the port specs only
        (whatever reads ports syncs them first)."""
        src, dst = self._component(connection.src_comp), self._component(connection.dst_comp)

        def where() -> str:  # formatted for an error only: a large system adds many
            return "{}.{} -> {}.{}".format(*connection.key())

        if connection.src_port not in src.output_specs:
            raise ConfigurationError(f"{where()}: {src.name!r} has no output "
                                     f"{connection.src_port!r}"
                                     f"{_why_not(src, connection.src_port, src.output_specs)}"
                                     f"; outputs: {sorted(src.output_specs)}")
        if connection.dst_port not in dst.input_specs:
            raise ConfigurationError(f"{where()}: {dst.name!r} has no input "
                                     f"{connection.dst_port!r}"
                                     f"{_why_not(dst, connection.dst_port, dst.input_specs)}"
                                     f"; inputs: {sorted(dst.input_specs)}")
        src_spec = src.output_specs[connection.src_port]
        dst_spec = dst.input_specs[connection.dst_port]
        if PortType.EVENT in (src_spec.type, dst_spec.type):
            raise ConfigurationError(f"{where()}: EVENT ports are joined with an EventConnection")
        if src_spec.type not in _COMPATIBLE.get(dst_spec.type, set()):
            raise ConfigurationError(f"{where()}: a {src_spec.type.name} output cannot drive a "
                                     f"{dst_spec.type.name} input")
        try:
            if connection.convert_units:
                conversion(src_spec.unit, dst_spec.unit)
        except units.DimensionalityError as exc:
            raise ConfigurationError(f"{where()}: incompatible units {src_spec.unit!r} and "
                                     f"{dst_spec.unit!r}") from exc
        existing = self._drivers.get((dst.name, connection.dst_port))
        if existing is not None:
            raise ConfigurationError(f"{where()}: input {dst.name}.{connection.dst_port} is "
                                     f"already driven by {existing.src_comp}."
                                     f"{existing.src_port}")
        self._drivers[dst.name, connection.dst_port] = connection
        self.connections.append(connection)
        self.is_initialized = False

    def add_event_connection(self, connection: EventConnection) -> None:
        """Route an event indicator (or an FMI 3.0 output clock) of one component to an event
        input of another (or the same): when the indicator fires (the clock ticks), that
        input's handler runs. Where the destination port is a triggered input clock of an FMI
        3.0 Co-Simulation FMU, the source ticks that clock instead."""
        src, dst = self._component(connection.src_comp), self._component(connection.dst_comp)
        where = "{}.{} -> {}.{}".format(*connection.key())
        ticks = connection.dst_port in clock_names(dst, "triggered_clocks")
        if ticks and connection.src_port == OWN_EVENTS:
            raise ConfigurationError(f"{where}: a triggered clock ticks on an event indicator "
                                     "or an output clock, not on all of a component's own "
                                     "events")
        if connection.src_port in clock_names(src, "output_clocks"):
            pass
        elif connection.src_port == OWN_EVENTS:
            from ..components.fmu import FMUComponent

            if not isinstance(src, FMUComponent):
                raise ConfigurationError(f"{where}: {src.name!r} handles no events of its own "
                                         "(FMU components do: an FMI 3.0 FMU's events, a Model "
                                         "Exchange FMU's state, time and step events)")
        elif connection.src_port not in src.event_indicators:
            clocks = clock_names(src, "output_clocks")
            raise ConfigurationError(f"{where}: {src.name!r} has no event indicator "
                                     f"{connection.src_port!r}; indicators: "
                                     f"{sorted(src.event_indicators) or 'none'}"
                                     + (f", output clocks: {clocks}" if clocks else ""))
        spec = dst.input_specs.get(connection.dst_port)
        if not ticks and (spec is None or spec.type != PortType.EVENT):
            events = sorted(n for n, s in dst.input_specs.items() if s.type == PortType.EVENT)
            raise ConfigurationError(f"{where}: {dst.name!r} has no EVENT input "
                                     f"{connection.dst_port!r}; EVENT inputs: {events or 'none'}")
        self.event_connections.append(connection)
        self.is_initialized = False

    def add_clock_connection(self, source: str, clock: str) -> None:
        """Tick the triggered input clock `clock` ("Component.clock", of an FMI 3.0
        Co-Simulation FMU) at every tick of the output clock `source` ("Component.clock") or
        at every firing of the event indicator `source` ("Component.indicator"): the
        EventConnection between the two."""
        ends = [name.split(".", 1) for name in (source, clock)]
        if any(len(end) != 2 for end in ends):
            raise ConfigurationError(f"clock connection {source!r} -> {clock!r}: each end is "
                                     "'Component.clock'")
        (src_comp, src_port), (dst_comp, dst_port) = ends
        if dst_port not in clock_names(self._component(dst_comp), "triggered_clocks"):
            raise ConfigurationError(
                f"clock connection {source!r} -> {clock!r}: {dst_comp!r} has no triggered "
                f"input clock {dst_port!r}; triggered input clocks: "
                f"{clock_names(self._component(dst_comp), 'triggered_clocks') or 'none'}")
        self.add_event_connection(EventConnection(src_comp, src_port, dst_comp, dst_port))

    # ------------------------------------------------------------------ compiling
    def _compile(self, settings: tuple[int, int | None]) -> EnginePlan:
        """The plan of the system as it is now, with the algorithm's options and initialize's
        `settings` (allow_non_finite, output_interval), built into an engine system."""
        algorithm = self.algorithm
        algorithm.validate()
        for connection in self.event_connections:
            listener = self.components[connection.dst_comp]
            if _ticks_clock(listener, connection):
                continue
            if not listener.has_event_handling():
                raise ConfigurationError(
                    f"{listener.name!r} receives {connection.src_comp}.{connection.src_port} "
                    "but handles no events: override _handle_events_internal or call "
                    f"add_event_handler({connection.dst_port!r}, handler)")
        hybrid = any(c.event_indicators for c in self.components.values())
        for component in self.components.values():
            reason = component.why_no_rollback() if hybrid else ""
            if reason and not component.can_rollback():
                raise ConfigurationError(
                    f"{component.name!r} cannot roll back, which locating events needs (the "
                    f"system has event indicators): {reason}")
            if component.event_indicators and not component.can_rollback():
                raise ConfigurationError(
                    f"{component.name!r} has event indicators but cannot roll back: its FMU "
                    "does not declare canGetAndSetFMUstate and it overrides no "
                    "snapshot_state/restore_state pair")
            component._event_routes = {}
        for connection in self.event_connections:
            if _ticks_clock(self.components[connection.dst_comp], connection):
                continue
            routes = self.components[connection.dst_comp]._event_routes
            routes.setdefault(connection.src_port, set()).add(connection.dst_port)
        plan = EnginePlan(self.name, self.components)
        for c in self.connections:
            src_spec = self.components[c.src_comp].output_specs[c.src_port]
            dst_spec = self.components[c.dst_comp].input_specs[c.dst_port]
            scale, offset = conversion(src_spec.unit, dst_spec.unit) if c.convert_units \
                else (1.0, 0.0)
            plan.connect(*c.key(), c.factor * scale, c.factor * offset + c.offset)
        for component in self.components.values():
            for event in component.event_indicators:
                plan.add_indicator(component, event)
        for c in self.event_connections:
            plan.add_event_connection(c.src_comp, c.src_port, c.dst_comp,
                                      own=c.src_port == OWN_EVENTS, dst_port=c.dst_port)
        for component in self.components.values():
            for event in component.self_handled_events():
                plan.add_event_connection(component.name, event, component.name)
        analysis = analyze_system(self)
        _warn_undeclared_dependencies(self.name, analysis)
        order, sizes, loops = analysis.schedule()
        if order:
            members = iter(order)
            plan.records.add("schedule", [(size, bool(loop), *(plan.index[next(members)]
                                                               for _ in range(size)))
                                          for size, loop in zip(sizes, loops, strict=True)],
                             about=f"{self.name}: schedule")
        run_algorithm = self._run_algorithm(plan)
        coupling = coupling_of(run_algorithm)
        ends = _power_bond_ends(plan, coupling.step_control) \
            if coupling.step_control is not None else []
        plan.build(option_records(run_algorithm, ends), setting_records(settings))
        plan.options, plan.initialize_settings = _options(run_algorithm), settings
        self._observer_ids = {id(o): add_observer(plan, o) for o in self._observers}
        return plan

    def _structure(self) -> tuple[Any, ...]:
        """What the engine plan is compiled from: the components (by identity and class) with
        their port and feedthrough counts, their handlers and their indicators, the connections and
        the event connections. Equal before two initializes, the plan is reused. Cheap: it is
        taken at every initialize."""
        components = tuple([
            (name, id(c), type(c), len(c.input_specs), len(c.output_specs),
             len(c.direct_feedthrough), len(getattr(c, "_declared_outputs", ())),
             tuple(id(h) for hs in c.event_handlers.values() for h in hs)
             if c.event_handlers else (),
             tuple(c.event_indicators.values()) if c.event_indicators else ())
            for name, c in self.components.items()])
        connections = tuple((*c.key(), c.factor, c.offset, c.convert_units)
                            for c in self.connections)
        return components, connections, tuple(c.key() for c in self.event_connections), \
            self._undeclared_dependencies

    def _reusable_plan(self) -> EnginePlan | None:
        """The plan of the last initialize when nothing it was compiled from changed and every
        component is still bound to it, else None."""
        plan = self._plan
        if plan is None or plan.left is not None or self._plan_structure != self._structure():
            return None
        return plan

    def _run_algorithm(self, plan: EnginePlan) -> Algorithm:
        """The algorithm, found without looking at every component: a plan with indicators
        runs the hybrid algorithm (what `algorithm` makes of a coupling one)."""
        if plan.indicators and not isinstance(self._algorithm, HybridAlgorithm):
            return self.algorithm
        return self._algorithm

    def _push_options(self, plan: EnginePlan) -> None:
        """The algorithm's options into the engine, checked first; nothing to do when the
        plan holds them already (a reused plan, a second run)."""
        algorithm = self._run_algorithm(plan)
        options = _options(algorithm)
        if options == plan.options:
            return
        algorithm.validate()
        coupling = algorithm.coupling if isinstance(algorithm, HybridAlgorithm) else algorithm
        plan.check(lib().ssx_set_coupling(plan.sys, coupling.coupling_value()), "coupling")
        plan.check(lib().ssx_set_loop_options(plan.sys, coupling.tolerance, coupling.max_iter,
                                              coupling.damping), "loop options")
        plan.check(lib().ssx_set_loop_jacobian(
            plan.sys, loop_jacobians()[coupling.loop_jacobian]), "loop Jacobian")
        plan.check(lib().ssx_set_threads(plan.sys, coupling.threads), "threads")
        plan.check(lib().ssx_set_input_order(plan.sys, coupling.input_order), "input order")
        plan.check(lib().ssx_set_extrapolate_held_inputs(
            plan.sys, int(coupling.extrapolate_held_inputs)), "held input extrapolation")
        # None switches off a step control an earlier run of this plan set
        control = coupling.step_control.engine_struct() if coupling.step_control is not None \
            else ffi.new("ssx_step_control *", {"enabled": 0})
        plan.check(lib().ssx_set_step_control(plan.sys, control), "step control")
        ends = _power_bond_ends(plan, coupling.step_control) \
            if coupling.step_control is not None else []
        plan.check(lib().ssx_set_power_bonds(plan.sys, len(ends) // 4,
                                             ffi.new("int[]", ends or [0])), "power bonds")
        if isinstance(algorithm, HybridAlgorithm):
            plan.check(lib().ssx_set_hybrid_options(
                plan.sys, algorithm.tol_time, algorithm.tol_value, algorithm.max_iter,
                algorithm.max_microsteps, int(algorithm.record_internal_steps),
                algorithm.locator(), algorithm.zeno_min_interval),
                "hybrid options")
        plan.options = options

    # ------------------------------------------------------------------ running
    def initialize(self, t0: float = 0.0, tolerance: float | None = None, *,
                   allow_non_finite: bool | None = None, output_interval: int | None = None
                   ) -> None:
        """Build the engine system, initialize every component at t0, record the first sample.

        Args:
            t0: the start time.
            tolerance: the relative tolerance of FMUs given none of their own (default: each
                FMU's DefaultExperiment tolerance).
            allow_non_finite: record NaN and infinite outputs instead of stopping the run at
                the first one (None keeps the engine's default: stop).
            output_interval: record every output_interval-th communication point (from t0),
                the last point of each run and every event instant; 1 records every point
                (None keeps the engine's default, every point).
        """
        t0 = _time_value(self.name, "t0", t0)
        plan = self._reusable_plan()
        settings = (int(bool(allow_non_finite)), output_interval)
        if plan is None:
            structure = self._structure()
            plan = self._compile(settings)
            self._plan, self._plan_structure = plan, structure
        else:
            plan.restart()
            if self._history_off:  # a run switched the history off
                keep_history_samples(plan, True)
        # a reused plan's options and settings may have changed since it was built
        self._push_options(plan)
        if settings != plan.initialize_settings:  # a reused plan holds them mostly
            plan.initialize_settings = None  # unknown until both are taken
            plan.check(lib().ssx_set_allow_non_finite(plan.sys, settings[0]),
                       "allow_non_finite")
            plan.check(lib().ssx_set_output_interval(
                plan.sys,
                defaults().output_interval if output_interval is None else output_interval),
                "output_interval")
            plan.initialize_settings = settings
        self.termination = None
        start_tables(self.components, self.connections, plan, t0)
        for component in self.components.values():
            component._start(t0, tolerance)
        if plan.initialize(t0) < 0:
            raise_failure(plan)
        warn_non_finite_outputs(plan)
        warn_coupling_fallbacks(plan)
        self.history = SystemHistory(system=self)
        self.t = t0
        self.is_initialized = True
        self._history_off = False

    def restart_recording(self, t: float) -> None:
        """Continue from t with the components as they are now (a component restored to a
        checkpoint): the history restarts with the sample at t."""
        if self._plan is None:
            raise ConfigurationError(f"{self.name}: call initialize(t0) first")
        if self._plan.initialize(t) < 0:
            raise_failure(self._plan)
        self.history = SystemHistory(system=self)
        self.t = t

    def run_members(self, values: Mapping[str, Sequence[float]], t0: float, tf: float,
                    dt: float, tolerance: float | None = None) -> MemberRuns:
        """Members of an ensemble on this System, one after another: member k sets each
        "Component.parameter" of `values` to its k-th value, initializes at t0 and runs to tf
        with step dt. Their samples, stacked (runs[k] is member k's). Where the engine can
        start every component itself (member_runs.py says when), the members run in the engine
        after an initialize with the first member's values, else each is set_parameters,
        initialize and run. Either way the histories are what that loop gives, and the System
        is left as the loop leaves it: initialized, the last member run, its parameters set.
        Ctrl-C stops the members within about a second with RunInterrupted, SIGTERM with
        RunTerminated; their `partial_result` holds the members finished."""
        names, table = member_table(self, values)
        if len(table) == 0:
            return MemberRuns.stacked([])
        set_member_parameters(self, names, table[0])
        self.initialize(t0, tolerance)
        plan = self._plan
        assert plan is not None
        if not engine_runs_members(self, names) or not exact_table(self, names, table):
            samples = []
            for k, row in enumerate(table):
                if k > 0:
                    set_member_parameters(self, names, row)
                    self.initialize(t0, tolerance)
                self.run(t0, tf, dt)
                samples.append(member_samples(plan))
            return MemberRuns.stacked(samples)
        t0, tf, dt = (_time_value(self.name, "t0", t0), _time_value(self.name, "tf", tf),
                      _time_value(self.name, "dt", dt))
        _check_step(self.name, t0, tf, dt)
        grid_steps = _grid_steps(self.name, None, dt)
        if grid_steps != plan.run_output_interval:
            plan.check(lib().ssx_set_run_output_interval(plan.sys, grid_steps), "output_interval")
            plan.run_output_interval = grid_steps
        plan.timeout = plan.deadline = plan.progress = None
        members = EngineMembers(self, names)
        set_member_parameters(self, names, table[-1])  # the System as the loop leaves it
        plan.waiting_parameters.clear()
        one_call, finished = runs_in_one_call(plan), []
        with sigterm_stops_the_run() as termination:
            try:
                if one_call:
                    runs = members.run_all(table, t0, tf, dt)
                else:
                    for row in table:
                        finished.append(members.run(row, t0, tf, dt))
                    runs = MemberRuns.stacked(finished)
            except KeyboardInterrupt as stop:  # Ctrl-C or SIGTERM: the finished members kept
                self._take_members_run(plan)
                partial = members.kept() if one_call else MemberRuns.stacked(finished)
                message = (f"system {self.name!r}: the members were stopped after "
                           f"{len(partial)} of {len(table)} (partial_result holds those)")
                if termination.requested:
                    raise RunTerminated(message, partial) from stop
                raise RunInterrupted(message, partial) from stop
        self._take_members_run(plan)
        plan.ran(self.t)
        return runs

    def _take_members_run(self, plan: EnginePlan) -> None:
        """The System's history and time are the last member's, as the engine left them."""
        self.history = SystemHistory(
            RecordedEvents(plan, int(lib().ssx_event_count(plan.sys))), self)
        self.t = float(lib().ssx_time(plan.sys))

    # ------------------------------------------------------------------ observers
    def add_observer(self, observer: Any) -> Any:
        """Call `observer` as the system runs (libcosim's observers): its
        step_complete(t, micro, values) at every sample the history keeps (values: a new numpy
        array of every component's outputs, named by the `columns` given to start), and where
        it has them start(t0, columns) at initialize, state_restored(t) when localization goes
        back to t (the samples after t were trials), event(t, micro, component, event) for each
        handled event, run_end() when a run returns. An exception raised in one stops the run
        and is raised by it. Added after initialize, it starts with the next run. Returns the
        observer."""
        if not callable(getattr(observer, "step_complete", None)):
            raise ConfigurationError(f"{self.name}: an observer needs a step_complete(t, micro, "
                                     f"values) method, {observer!r} has none")
        self._observers.append(observer)
        if self._plan is not None:
            self._observer_ids[id(observer)] = add_observer(self._plan, observer)
        return observer

    def remove_observer(self, observer: Any) -> None:
        """Stop calling an observer added by add_observer."""
        if observer not in self._observers:
            raise ConfigurationError(f"{self.name}: {observer!r} is not an observer of it")
        self._observers.remove(observer)
        engine_id = self._observer_ids.pop(id(observer), None)
        if self._plan is not None and engine_id is not None:
            remove_observer(self._plan, engine_id)

    def run(self, t0: float, tf: float, dt: float,
            progress: bool | ProgressCallback | None = None, timeout: float | None = None,
            output_interval: float | None = None, stream_to: Any = None,
            keep_history: bool = True) -> SimulationResult:
        """Simulate on the grid t0 + k*dt (the last point exactly tf) plus event instants.

        Ctrl-C stops a run within about 0.1 s with KeyboardInterrupt (RunInterrupted); the
        samples recorded up to the last completed step stay readable through get_history().
        SIGTERM stops it the same way with RunTerminated, a SystemExit (unless the program set
        its own SIGTERM handler).

        Args:
            t0: the start time: where the system is (initialize's t0 or the last run's tf).
            tf: the end time.
            dt: the communication step.
            progress: SysSimX's callback progress(t, tf), called with the time reached about
                every 50 ms of wall time and once at the end of the run; or True for a
                terminal bar that appears after a second.
            timeout: seconds of wall time after which the run stops with
                SimulationTimeoutError (None: no limit).
            output_interval: a time, a whole multiple of dt (FMPy's meaning): this run records
                t0 + j*output_interval, its last point and every event instant (None: what
                initialize's output_interval says).
            stream_to: write the run's samples to disk while it runs, exactly the history's
                (from the state it starts at): a path whose suffix chooses the format (.csv,
                .parquet, .nc), or a writer object of yours with write(t, micro, values) (and
                optionally start(columns)) that you close, which may take several runs.
            keep_history: False keeps no samples in memory from this run on (until the next
                initialize): with stream_to, a run larger than memory keeps every sample on
                disk.

        Returns:
            The run's samples, events and statistics.
        """
        if not self.is_initialized or self._plan is None:
            raise ConfigurationError(f"{self.name}: call initialize(t0) before run()")
        if self._plan.waiting_parameters:
            _warn_waiting_parameters(self._plan.waiting_parameters)
        t0, tf, dt = (_time_value(self.name, "t0", t0), _time_value(self.name, "tf", tf),
                      _time_value(self.name, "dt", dt))
        if timeout is not None and not (isinstance(timeout, int | float) and timeout > 0):
            raise ConfigurationError(f"{self.name}: timeout must be a positive number of "
                                     f"seconds or None, got {timeout!r}")
        _check_step(self.name, t0, tf, dt)
        grid_steps = _grid_steps(self.name, output_interval, dt)
        if not math.isclose(t0, self.t, rel_tol=0.0, abs_tol=1e-12 * max(1.0, abs(t0))):
            raise ConfigurationError(f"{self.name}: run starts at t0={t0} but the system is at "
                                     f"t={self.t}")
        reports = run_progress(progress, self.name, t0, tf)
        plan = self._plan
        if plan.left is not None:
            raise ConfigurationError(
                f"{self.name}: component {plan.left!r} was initialized elsewhere since "
                "this system's initialize; call initialize again")
        if keep_history and self._history_off:
            raise ConfigurationError(f"{self.name}: an earlier run kept no history "
                                     "(keep_history=False); call initialize to keep it again")
        self._push_options(plan)
        if grid_steps != plan.run_output_interval:
            plan.check(lib().ssx_set_run_output_interval(plan.sys, grid_steps), "output_interval")
            plan.run_output_interval = grid_steps
        # a run the engine will refuse opens no stream: its file (perhaps an earlier run's)
        # is left as it is
        stream = RunStream(plan, stream_to, t0, self._streamed) \
            if stream_to is not None and _engine_accepts(t0, tf, dt) else None
        if not keep_history:
            keep_history_samples(plan, False)
            self._history_off = True
        logger.info("Starting simulation run from t=%s to t=%s with dt=%s", t0, tf, dt)
        start = time.perf_counter()
        plan.timeout = timeout
        plan.deadline = time.monotonic() + timeout if timeout is not None else None
        plan.progress = reports.report if reports is not None else None
        try:
            with sigterm_stops_the_run() as termination:
                status = lib().ssx_run(plan.sys, t0, tf, dt)
        finally:
            plan.progress = None
            if stream is not None:
                stream.finish()
        wall = time.perf_counter() - start
        warn_non_finite_outputs(plan)
        warn_coupling_fallbacks(plan)
        outcome = RunOutcome(plan)
        events = RecordedEvents(plan, outcome.event_count)
        self.history = SystemHistory(events, self)
        self.t = outcome.time
        if status < 0:
            if reports is not None:
                reports.close()
            try:
                raise_failure(plan)
            except KeyboardInterrupt as stop:  # Ctrl-C: the steps completed are the result
                for component in self.components.values():
                    component.t = self.t
                partial = SimulationResult.from_system(self, t0, self.t, dt, wall, outcome)
                kept = "partial_result holds the samples up to there" if keep_history \
                    else "keep_history=False: partial_result holds no samples" + (
                        "" if stream_to is None else f"; they are all in {stream_to!r}")
                if termination.requested:
                    raise RunTerminated(f"system {self.name!r}: SIGTERM stopped the run at "
                                        f"t={self.t:.12g} ({kept})", partial) from stop
                raise RunInterrupted(f"system {self.name!r}: the run was interrupted at "
                                     f"t={self.t:.12g} ({kept})", partial) from stop
        if reports is not None:
            reports.finish(self.t)
        self.termination = read_termination(plan, outcome.termination)
        if self.termination is not None:
            plan.failure = None  # what a hook raised because the component stopped
            logger.info("%s: %s; the run ends at t=%s", self.name, self.termination, self.t)
        plan.ran(self.t)
        algorithm = self._run_algorithm(plan)
        if isinstance(algorithm, HybridAlgorithm):
            log_events(events, t0, algorithm.method)
        logger.info("Simulation completed in %.2f seconds", wall)
        return SimulationResult.from_system(self, t0, tf, dt, wall, outcome)

    def _mode_switches(self) -> dict[str, tuple[Any, ...]]:
        """{component: (ModeSwitchEvent, ...)} of the components that switched models."""
        names = self._plan.switching if self._plan is not None else self.components
        if not names:
            return {}
        switches = {n: self.components[n].history.mode_switch_events for n in names}
        return {n: events for n, events in switches.items() if events}

    # ------------------------------------------------------------------ results
    def get_history(self) -> dict[str, Any]:
        """{component: (t, {output: values})} of everything recorded since initialize (also
        after a failed run), plus "Events": {(component, event): [DenseTime]} and
        "ModeSwitches": {component: (ModeSwitchEvent, ...)}."""
        if self._plan is None:
            raise ConfigurationError(f"{self.name}: nothing recorded yet; call initialize")
        view = HistoryView(self._plan, self.history.recorded_events)
        history: dict[str, Any] = {name: view[name] for name in self.components}
        history["Events"] = self.history.get_all_event_histories()
        history["ModeSwitches"] = self._mode_switches()
        return history

    def history_bytes(self) -> int:
        """Memory the engine holds for the recorded history."""
        return int(lib().ssx_history_bytes(self._plan.sys)) if self._plan is not None else 0

    # ------------------------------------------------------------------ state
    def _initialized_plan(self, what: str) -> EnginePlan:
        if self._plan is None or not self.is_initialized:
            raise StateError(f"{self.name}: call initialize(t0) before {what}")
        return self._plan

    def save_state(self) -> SystemState:
        """The whole system's state now (every component's, and the engine's between steps);
        raises StateError naming a component that cannot save its state (a Python component,
        an FMU without canGetAndSetFMUstate)."""
        return save_state(self._initialized_plan("save_state"))

    def restore_state(self, state: SystemState) -> None:
        """Put the system back into `state` (saved from it since it was last built): its time
        and termination become the state's; running on repeats what followed the save. The
        history is not rewound: samples recorded since the save stay, later ones follow."""
        plan = self._initialized_plan("restore_state")
        self.t, self.termination = restore_state(plan, state)
        plan.ran(self.t)

    def state_from_bytes(self, data: bytes) -> SystemState:
        """The state that SystemState.to_bytes turned into `data`, for this system (built as
        the one it was saved from); restore it with restore_state."""
        return state_from_bytes(self._initialized_plan("state_from_bytes"), data)

    def to_ssp(self, path: str | Path, start_time: float | None = None,
               stop_time: float | None = None, step_size: float | None = None) -> Path:
        """Write the system (FMU components only) as an SSP 1.0 archive; the times become its
        default experiment, the step the Open Simulation Platform's fixed step annotation."""
        from ..ssp_format.experiment import Experiment
        from ..ssp_format.writer import write_ssp

        return write_ssp(self, path, Experiment(start_time, stop_time, step_size))

    def to_plan(self, folders: Mapping[str, str | Path] | None = None) -> str:
        """The system as a plan (the text of docs/reference/plan-format.md), from which the
        engine builds, initializes and runs it without Python: its components, connections,
        events, schedule, algorithm and the settings of the last initialize, each FMU's
        experiment and the parameters set on it. An FMU's folder is `folders[name]` (relative
        to the base folder the plan is built from), else the folder syssimx unpacked it to,
        which lives as long as the component. A Python component, Python hooks and an
        indicator function are placeholders, which a build without Python refuses."""
        plan = self._reusable_plan()
        if plan is None:
            structure = self._structure()
            settings = self._plan.initialize_settings if self._plan is not None else None
            plan = self._compile(settings or (0, None))
            self._plan, self._plan_structure = plan, structure
        algorithm = self._run_algorithm(plan)
        control = coupling_of(algorithm).step_control
        ends = _power_bond_ends(plan, control) if control is not None else []
        return plan_text(plan, algorithm, ends, folders)

    def write_plan(self, path: str | Path,
                   folders: Mapping[str, str | Path] | None = None) -> Path:
        """Write `to_plan(folders)` to the file `path` (whole or not at all); returns it."""
        return write_text(path, self.to_plan(folders))

    def export_fmu(self, path: str | Path, fmi_version: str = "2.0",
                   inputs: Sequence[str] | None = None, outputs: Sequence[str] | None = None,
                   parameters: Sequence[str] = (), **experiment: float | None) -> Path:
        """Write the system as one Co-Simulation FMU (FMI "2.0" or "3.0") whose binary is the
        engine; ports and parameters are named "Component.port" (see
        syssimx.export.export_fmu for the defaults and `experiment`: step_size, start_time,
        stop_time). A system that runs Python anywhere is refused, naming each part."""
        from ..export import export_fmu

        return export_fmu(self, path, fmi_version, inputs, outputs, parameters, **experiment)

    def describe(self) -> str:
        """The system's structure as text: components and their ports with units, connections,
        event connections, execution order and algebraic loops."""
        from ..graph.describe import describe_system

        return describe_system(self)

    def _repr_svg_(self) -> str | None:
        """Jupyter shows the system as its graph (graphviz is imported only here: optional).
        A display never raises: without graphviz or its `dot` program this is None, and
        Jupyter shows the text repr."""
        try:
            from ..viz.system_graph_visualizer import system_svg

            return system_svg(self)
        except (ImportError, RuntimeError) as error:
            logger.debug("%s: shown as text: %s", self.name, error)
            return None

    def _repr_pretty_(self, printer: Any, cycle: bool) -> None:
        """IPython's text of the system (what Jupyter shows when _repr_svg_ has no picture):
        the repr, and below it how to get the picture when it cannot be drawn."""
        from ..viz.drawing_support import why_no_drawing

        printer.text(repr(self))
        reason = why_no_drawing()
        if reason is not None:
            printer.text("\n" + reason)

    def reset(self) -> None:
        """Drop the engine system; components keep their parameters and observers."""
        self._plan = self._plan_structure = None
        self._observer_ids = {}
        self.is_initialized = False
        self.history = SystemHistory(system=self)
        self.termination = None
        for component in self.components.values():
            component.reset()


def _ticks_clock(listener: CoSimComponent, connection: EventConnection) -> bool:
    """Whether the connection ticks a triggered input clock of its listener (no handler)."""
    return connection.dst_port in clock_names(listener, "triggered_clocks")


def _power_bond_ends(plan: EnginePlan, control: StepControl) -> list[int]:
    """The engine's (component, input) indices of the bonds' ends, four per bond."""
    ends = []
    for bond in control.power_bonds:
        for component, port in bond:
            if component not in plan.index or port not in plan.inputs[component]:
                raise ConfigurationError(
                    f"step_control.power_bonds: {component}.{port} is not an input of this "
                    f"system; components: {sorted(plan.index)}")
            ends += [plan.index[component], plan.inputs[component].index(port)]
    return ends


def _options(algorithm: Algorithm) -> tuple[Any, ...]:
    """An algorithm's options as values (its coupling's included): equal, the engine holds
    them already. Taken at every initialize and run."""
    coupling = algorithm.coupling if isinstance(algorithm, HybridAlgorithm) else None
    return (type(algorithm), *_option_values(algorithm, every=False), type(coupling),
            *(_option_values(coupling, every=True) if coupling is not None else ()))


def _option_values(options: Any, every: bool) -> tuple[Any, ...]:
    """The values of an options object's fields, a StepControl as its values at this moment
    (it may be changed in place later); without `every` only options (no nested objects).
    Plain values only, the common case, take no Python per field."""
    values = tuple(vars(options).values())
    if _OPTION_TYPES.issuperset(map(type, values)):
        return values
    return tuple(dataclasses.astuple(v) if isinstance(v, StepControl) else v for v in values
                 if every or type(v) in _OPTION_TYPES or isinstance(v, StepControl))


_OPTION_TYPES = frozenset((float, int, str, bool, type(None)))


def _time_value(system: str, label: str, value: object) -> float:
    """A time or step as a float: any real number (numpy scalars too), finite."""
    if type(value) is float and math.isfinite(value):  # the common case, without the ABC
        return value
    if isinstance(value, bool) or not isinstance(value, numbers.Real) \
            or not math.isfinite(value):
        raise ConfigurationError(f"{system}: {label} must be a finite number, got {value!r}")
    return float(value)


def _why_not(component: CoSimComponent, port: str, ports: Any) -> str:
    """Why a known name is no port, else the close port names."""
    return component.why_no_port(port) or did_you_mean(port, ports)


def _check_step(system: str, t0: float, tf: float, dt: float) -> None:
    """A step longer than the run is refused (a swapped tf and dt, most often); one that does
    not divide the run is taken, its last step shorter so that the run ends at tf exactly, as
    FMPy's, with a warning. (dt <= 0 is the engine's to refuse, with its own message.)"""
    span = tf - t0
    if not (dt > 0 and span > 0):
        return
    if dt > span * (1 + 1e-9):
        raise ConfigurationError(f"{system}: dt={dt!r} is longer than the run from t0={t0!r} "
                                 f"to tf={tf!r}; give dt <= tf - t0 (run takes t0, tf, dt)")
    steps = span / dt
    if abs(steps - round(steps)) > 1e-9 * max(1.0, steps):
        last = span - math.floor(steps) * dt
        warnings.warn(f"{system}: dt={dt!r} does not divide tf - t0 = {span!r}: the last step "
                      f"is {last:.6g} s, so that the run ends at tf={tf!r}", SysSimXWarning,
                      stacklevel=3)


# the most grid steps the engine takes in one run (SSX_MAX_GRID_STEPS)
MAX_GRID_STEPS = 1e12


def _engine_accepts(t0: float, tf: float, dt: float) -> bool:
    """Whether ssx_run takes these times (its checks of them, made before anything runs)."""
    return dt > 0 and tf >= t0 and (tf - t0) / dt <= MAX_GRID_STEPS


def _grid_steps(system: str, output_interval: object, dt: float) -> int:
    """run()'s output_interval as a number of grid steps (0 for None; for dt <= 0 too, which
    the engine refuses with its own message)."""
    if output_interval is None or not dt > 0:
        return 0
    interval = _time_value(system, "output_interval", output_interval)
    steps = round(interval / dt)
    if steps < 1 or abs(interval / dt - steps) > 1e-9 * steps:
        raise ConfigurationError(f"{system}: output_interval={interval!r} is not a whole "
                                 f"multiple of dt={dt!r}")
    return steps


def _warn_waiting_parameters(waiting: dict[str, tuple[str, ...]]) -> None:
    """Once per parameter set on a running FMU: this run does not use it."""
    for component, names in waiting.items():
        warnings.warn(f"{component}.set_parameters({', '.join(names)}) after initialize: the "
                      "running FMU keeps its values; they apply at the next initialize (or "
                      "reinitialize)", SysSimXWarning, stacklevel=3)
    waiting.clear()


def _warn_undeclared_dependencies(name: str, analysis: SystemAnalysis) -> None:
    """One warning when a loop exists only because FMUs declare no output dependencies."""
    members = analysis.undeclared_in_loops
    if not members:
        return
    fmus = ", ".join(repr(member) for member in members)
    how = ("declare each output's dependencies: in the FMU's modelDescription.xml "
           "(FMI 2.0/3.0: ModelStructure/Outputs/Unknown dependencies=\"...\", empty for "
           "none; FMI 1.0: an output's <DirectDependency>), with "
           "component.declare_dependencies(output=[inputs]) or a YAML component's "
           "'dependencies: {output: [inputs]}'")
    if analysis.undeclared_dependencies == "all":
        warnings.warn(
            f"{name}: {fmus} declare no output dependencies, so by the standard every output "
            "depends on every input, which makes an algebraic loop that is solved at every "
            f"communication point; {how}, or couple the loop explicitly as libcosim does with "
            "System(..., undeclared_dependencies=\"none\") (a YAML file's system: "
            "{undeclared_dependencies: none})", SysSimXWarning, stacklevel=4)
    else:
        warnings.warn(
            f"{name}: {fmus} declare no output dependencies; with undeclared_dependencies="
            "\"none\" their outputs are taken to depend on no input and the loop the "
            "standard's assumption would make is coupled explicitly, without iterations; "
            f"{how} for the exact structure", SysSimXWarning, stacklevel=4)
