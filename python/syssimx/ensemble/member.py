"""One member of an ensemble, run where it is scheduled (a worker process, or in process).

A member takes its System (the one its process kept from the ensemble's previous member, or a
fresh one), sets its parameters, initializes and runs it. Whatever goes wrong inside (a failing
FMU, an exception in the builder or a handler, a run past its timeout) becomes the member's
result: status "failed" with the error, and the samples recorded before the failure. Only a
crash of the process itself is left to the caller to report.
"""

from __future__ import annotations

import os
import socket
import time
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..bridge.failure import raise_failure
from ..bridge.run_outcome import RunOutcome
from ..errors import ConfigurationError, SysSimXWarning
from ..system.member_runs import EngineMembers
from ..system.recorded_events import RecordedEvents
from ..system.results import SimulationResult
from ..system.run_signals import sigterm_stops_the_run
from ..system.system import System
from ..system.system_history import SystemHistory
from ..system.termination import read_termination
from .loaded_fmus import loaded_fmus
from .members import ParameterSet, split_name
from .reused_system import reused_system, user_values
from .system_source import SystemSource

STATISTICS = ("macro_steps", "do_step_calls", "state_saves", "state_restores", "events",
              "localization_iterations")


@dataclass(frozen=True)
class MemberTask:
    """What a member runs: its index, parameter values and the experiment. `timeout` is the
    wall time its run may take; `topic` names the event stream its start is announced on;
    `ensemble` names the ensemble whose members may run on one System per process."""

    index: int
    parameters: ParameterSet
    t0: float
    tf: float
    dt: float
    outputs: tuple[str, ...] | None = None
    timeout: float | None = None
    topic: str | None = None
    ensemble: str | None = None


@dataclass
class MemberResult:
    """A member's outcome. `time`, `micro` and `outputs` ("Component.port" -> values) are the
    member's own samples (the grid plus its event instants); `events` are (t, micro,
    "Component.event"). A failed member keeps what it recorded before the failure."""

    index: int
    parameters: ParameterSet
    status: str  # "ok" or "failed"
    error: str = ""
    error_type: str = ""
    time: np.ndarray = field(default_factory=lambda: np.empty(0))
    micro: np.ndarray = field(default_factory=lambda: np.empty(0, dtype=np.int64))
    outputs: dict[str, np.ndarray] = field(default_factory=dict)
    events: tuple[tuple[float, int, str], ...] = ()
    statistics: dict[str, int] = field(default_factory=dict)
    termination: str = ""
    wall_time: float = float("nan")
    worker: str = ""

    @property
    def ok(self) -> bool:
        """Whether the member's run completed."""
        return self.status == "ok"


def run_member(build: SystemSource, task: MemberTask) -> MemberResult:
    """Run one member here and return its result; never raises for a member's own failure.
    A task of an ensemble runs on the System this process kept from the ensemble's previous
    member when there is one (reused_system.py), else on a fresh one from `build`."""
    _announce(task)
    start = time.perf_counter()
    worker = f"{socket.gethostname()}:{os.getpid()}"
    system: System | None = None
    run: SimulationResult | None = None
    initialized = False  # a kept System holds the previous member's samples until then
    result = MemberResult(task.index, task.parameters, "ok", worker=worker)
    try:
        system = reused_system.take(task.ensemble, build)
        loaded_fmus.keep(system)
        engine = reused_system.engine_members(system, task.parameters)
        if engine is not None:
            before_run = user_values(system)
            initialized = True
            result.statistics, result.termination = _run_in_engine(system, engine, task)
        else:
            _set_parameters(system, task.parameters)
            before_run = user_values(system)
            initialized = True
            system.initialize(task.t0)
            run = system.run(task.t0, task.tf, task.dt, timeout=task.timeout)
            result.statistics = {name: int(getattr(run.statistics, name))
                                 for name in STATISTICS}
            result.termination = str(run.termination) if run.termination is not None else ""
    except Exception as error:  # the member's failure is its result; other members go on
        result.status, result.error_type = "failed", type(error).__name__
        result.error = f"{type(error).__name__}: {error}"
    if system is not None and initialized:
        _record(result, system, task.outputs, run)
        if result.ok:  # a failed member's System is dropped (an FMU may be broken)
            reused_system.give_back(task.ensemble, system, before_run)
    result.wall_time = time.perf_counter() - start
    return result


def _run_in_engine(system: System, engine: EngineMembers, task: MemberTask
                   ) -> tuple[dict[str, int], str]:
    """The member as one engine call on the kept System (its components' parameters in
    Python stay the previous member's: every member writes the same names). Its statistics
    and termination; the System's history and time are the member's, also when it failed
    (raised here, as System.run raises)."""
    plan = engine.plan
    plan.failure = None
    plan.timeout = task.timeout
    plan.deadline = time.monotonic() + task.timeout if task.timeout is not None else None
    with sigterm_stops_the_run():
        status = engine.start([float(value) for value in task.parameters.values()],
                              task.t0, task.tf, task.dt)
    outcome = RunOutcome(plan)
    system.history = SystemHistory(RecordedEvents(plan, outcome.event_count), system)
    system.t = outcome.time
    if status < 0:
        raise_failure(plan)
    termination = read_termination(plan, outcome.termination)
    system.termination = termination
    if termination is not None:
        plan.failure = None
    plan.ran(system.t)
    return ({name: int(getattr(outcome.statistics, name)) for name in STATISTICS},
            str(termination) if termination is not None else "")


def _announce(task: MemberTask) -> None:
    """Tell the client this member started, and where (it times the member from here)."""
    if task.topic is None:
        return
    from distributed import get_worker

    worker = get_worker()
    worker.log_event(task.topic, {"member": task.index, "worker": worker.address,
                                  "pid": os.getpid()})


def _set_parameters(system: System, parameters: ParameterSet) -> None:
    """"Component.name" -> value: a parameter, or an input held at that value."""
    for name, value in parameters.items():
        component_name, variable = split_name(name)
        component = system.components.get(component_name)
        if component is None:
            raise ConfigurationError(f"{name}: the system {system.name!r} has no component "
                                     f"{component_name!r}; components: "
                                     f"{sorted(system.components)}")
        if variable in component.input_specs:
            component.set_inputs({variable: value})
        else:
            with warnings.catch_warnings():  # a reused System: initialize comes next
                warnings.simplefilter("ignore", SysSimXWarning)
                component.set_parameters(**{variable: value})


def _record(result: MemberResult, system: System, outputs: tuple[str, ...] | None,
            run: SimulationResult | None) -> None:
    """Copy the member's samples and events out of its engine (the System dies here): from
    its run's result when the run returned one (the same views over the engine's samples that
    get_history would make again: 0.04 ms of a 1.2 ms seed member), else from get_history."""
    samples: SimulationResult | dict[str, Any]
    if run is not None:
        samples, instants = run, system.history.get_all_event_histories()
    else:
        try:
            samples = system.get_history()
        except ConfigurationError:  # it failed before initialize recorded anything
            return
        instants = samples["Events"]
    columns: dict[str, np.ndarray] = {}
    for component in system.components:
        t, values = samples[component]
        if result.time.size == 0:
            result.time = np.array(t, dtype=np.float64)
        for port, series in values.items():
            columns[f"{component}.{port}"] = np.array(series)
    if result.time.size:
        micro = run.micro if run is not None else system._plan.history().micro()
        result.micro = np.array(micro, dtype=np.int64)
    if outputs is not None:
        unknown = [name for name in outputs if name not in columns]
        if unknown and result.ok:
            result.status, result.error_type = "failed", "ConfigurationError"
            result.error = (f"ConfigurationError: unknown output(s) {unknown}; outputs: "
                            f"{sorted(columns)}")
        columns = {name: columns[name] for name in outputs if name in columns}
    result.outputs = columns
    result.events = tuple(sorted((instant.t, instant.micro, f"{component}.{event}")
                                 for (component, event), times in instants.items()
                                 for instant in times))
