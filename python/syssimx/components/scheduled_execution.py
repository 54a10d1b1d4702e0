"""ScheduledExecutionComponent: an FMI 3.0 Scheduled Execution FMU as a component of a System.

    clocks = ScheduledExecutionComponent("C", "Clocks.fmu")
    clocks.schedule_clock("inClock2", times=[0, 1, 8, 9])
    system.add_component(clocks)

or, the same in a YAML or JSON system (`clock_times` takes what schedule_clock does):

    components:
      - name: C
        class: syssimx:ScheduledExecutionComponent
        args: {fmu_path: Clocks.fmu, clock_times: {inClock2: [0, 1, 8, 9]}}

A Scheduled Execution FMU has no step: the importer activates the model partition of each
input clock at its ticks. syssimx schedules them in Python (fmu/fmi3_scheduled.py calls the
FMU):

- periodic input clocks (intervalVariability constant, fixed, tunable, changing) tick at their
  shift and every interval after it (the description's, else the FMU's fmi3GetIntervalDecimal
  after initialization; a tunable or changing interval is asked again after each tick);
- triggered input clocks tick at the times given to `schedule_clock`;
- countdown clocks tick when the FMU announces their interval (its clockUpdate callback, then
  fmi3GetIntervalDecimal): at the announcing tick's time plus that interval;
- output clocks are read with fmi3GetClock in the clockUpdate callback; their ticks are logged.

The step from t to t + dt activates, in order, every tick at or after t and before t + dt, so a
run from 0 to 10 s activates the ticks at 0 to 9 and the outputs at t + dt are those after the
step's ticks. Ticks at one instant run in priority order (the lowest `priority` value first,
then the lowest value reference), a countdown tick announced at that instant after the ones
due before it of higher priority: whatever the step size, the order is the same. The inputs are
set before each partition runs; after it, the outputs clocked by its clock or depending on it
(ModelStructure) are read, set on their ports and logged with the tick in `ticks`.
"""

from __future__ import annotations

import heapq
import math
import weakref
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..core.port import PortSpec, PortType
from ..errors import ConfigurationError, FMUFileError
from ..fmu.clocks import ClockInfo, ClockStructure
from ..fmu.description_fmi3 import clock_structure
from ..fmu.extraction import extractions
from ..fmu.fmi3_scheduled import C_TYPES, INTERVAL_CHANGED, ScheduledInstance
from ..fmu.info import PORT_TYPES
from ..fmu.standards import FMI3
from .base import CoSimComponent

_PERIODIC = ("constant", "fixed", "tunable", "changing")
_UNKNOWN_PRIORITY = 2**31  # a clock without priority runs after every clock with one


@dataclass(frozen=True)
class Tick:
    """One clock tick: an input clock's partition run, or an output clock read as ticked, with
    the outputs read after it (none for an output clock)."""

    time: float
    clock: str
    values: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class _Variable:
    name: str
    value_reference: int
    fmi_type: str
    causality: str


class ScheduledExecutionComponent(CoSimComponent):
    """An FMI 3.0 FMU that declares ScheduledExecution, run by activating its partitions."""

    def __init__(self, name: str, fmu_path: str | Path,
                 clock_times: Mapping[str, Iterable[float]] | None = None,
                 group: str | None = None) -> None:
        super().__init__(name, group=group)
        from fmpy import read_model_description

        self.fmu_path = Path(fmu_path).resolve()
        description = read_model_description(str(self.fmu_path), validate=False)
        if description.scheduledExecution is None:
            raise FMUFileError(f"{self.fmu_path}: the FMU declares no ScheduledExecution "
                               "(FMUComponent runs Co-Simulation and Model Exchange FMUs)")
        self.clocks: ClockStructure = clock_structure(self.fmu_path)
        self._identifier = description.scheduledExecution.modelIdentifier
        self._token = description.instantiationToken or ""
        self._variables = [_variable(v, self.fmu_path) for v in description.modelVariables
                           if v.causality in ("input", "output") and v.type != "Clock"]
        for variable in self._variables:
            specs = self.input_specs if variable.causality == "input" else self.output_specs
            specs[variable.name] = PortSpec(variable.name, PORT_TYPES[variable.fmi_type],
                                            "in" if variable.causality == "input" else "out")
        self._starts = {v.name: v.start for v in description.modelVariables
                        if v.causality == "input" and v.start is not None}
        self._triggered_times: dict[str, list[float]] = {}
        self.ticks: list[Tick] = []
        self._output_ticks: list[Tick] = []  # read during the running partition
        self._instance: ScheduledInstance | None = None
        self._finalizer: weakref.finalize | None = None
        self._queue: list[tuple[float, int, int, int]] = []  # time, priority, vr, sequence
        self._sequence = 0
        self._now = 0.0
        self._values: dict[str, Any] = {}
        self._periods: dict[str, float] = {}  # the FMU's intervals of periodic clocks
        self._sync_ports()
        for name_, value in self._starts.items():
            self.inputs[name_].set(_parsed(value, self.input_specs[name_].type), 0.0)
        for clock, times in (clock_times or {}).items():
            self.schedule_clock(clock, times)

    # ------------------------------------------------------------------ scheduling
    def schedule_clock(self, clock: str, times: Iterable[float]) -> None:
        """Tick the triggered input clock `clock` at `times` (seconds; replaces earlier
        times). Takes effect at the next initialize."""
        info = self._clock(clock)
        if info.causality != "input" or info.interval_variability != "triggered":
            raise ConfigurationError(
                f"component {self.name!r}: clock {clock!r} is {info.causality} with "
                f"intervalVariability {info.interval_variability}; schedule_clock takes the "
                "times of a triggered input clock (the others tick by their interval or by "
                "the FMU)")
        chosen = sorted(float(t) for t in times)
        if not all(math.isfinite(t) for t in chosen):
            raise ConfigurationError(f"component {self.name!r}: clock {clock!r} is given a "
                                     "time that is not a finite number")
        self._triggered_times[clock] = chosen

    def _clock(self, name: str) -> ClockInfo:
        try:
            return self.clocks.by_name(name)
        except KeyError as exc:
            raise ConfigurationError(f"component {self.name!r}: {exc.args[0]}") from None

    def _push(self, clock: ClockInfo, time: float) -> None:
        priority = _UNKNOWN_PRIORITY if clock.priority is None else clock.priority
        heapq.heappush(self._queue, (time, priority, clock.value_reference, self._sequence))
        self._sequence += 1

    # ------------------------------------------------------------------ lifecycle
    def _initialize_component(self, t0: float) -> None:
        self._release()
        unzip_dir, key = extractions.acquire(self.fmu_path, shareable=False)
        binary = extractions.binary(unzip_dir, FMI3().binary_name(self._identifier))
        if binary is None:
            extractions.release(unzip_dir, key)
            raise FMUFileError(f"{self.fmu_path}: {FMI3().binary_name(self._identifier)} is "
                               "not a file inside the extracted archive")
        resources = unzip_dir / "resources"
        try:
            instance = ScheduledInstance(binary, self.name, self._token,
                                         resources if resources.is_dir() else None,
                                         _weakly(weakref.WeakMethod(self._clock_update)))
        except BaseException:
            extractions.release(unzip_dir, key)
            raise
        self._instance = instance
        self._finalizer = weakref.finalize(self, _free, instance, unzip_dir, key)
        self._set_inputs()
        instance.initialize(t0)
        self.ticks = []
        self._queue, self._sequence, self._now, self._periods = [], 0, t0, {}
        for clock in self.clocks.clocks:
            if clock.causality != "input":
                continue
            if clock.interval_variability in _PERIODIC:
                self._push(clock, t0 + clock.first_tick)
            elif clock.interval_variability == "triggered":
                for time in self._triggered_times.get(clock.name, ()):
                    if time >= t0:
                        self._push(clock, time)
        self._values = self._read(self._variables_of(None))

    def _do_step_internal(self, t: float, dt: float) -> None:
        end = t + dt
        margin = 1e-9 * max(1.0, abs(end))  # a tick at end - rounding belongs to the next step
        while self._queue and self._queue[0][0] < end - margin:
            time, _, reference, _ = heapq.heappop(self._queue)
            self._activate(self.clocks.by_reference(reference), time)

    def _activate(self, clock: ClockInfo, time: float) -> None:
        instance = self._require_instance()
        self._now = time
        self._set_inputs()
        self._output_ticks = []
        instance.activate(clock.value_reference, time)
        values = self._read(self._variables_of(clock.value_reference))
        self._values.update(values)
        # the output clocks the partition ticked come after it in the log
        self.ticks += [Tick(time, clock.name, values), *self._output_ticks]
        if clock.interval_variability in _PERIODIC:
            period = self._period(clock)
            self._push(clock, time + period)

    def _period(self, clock: ClockInfo) -> float:
        """The interval to the clock's next tick: the description's for a constant or fixed
        clock that gives one, else the FMU's latest changed interval."""
        known = self._periods.get(clock.name, clock.period)
        if clock.interval_variability in ("constant", "fixed") and known is not None:
            return known
        interval, qualifier = self._require_instance().intervals([clock.value_reference])[0]
        if qualifier == INTERVAL_CHANGED:
            if not (math.isfinite(interval) and interval > 0):
                raise FMUFileError(f"{self.fmu_path}: fmi3GetIntervalDecimal gives periodic "
                                   f"clock {clock.name!r} the interval {interval}; an interval "
                                   "is a positive number of seconds")
            known = self._periods[clock.name] = interval
        if known is None:
            raise FMUFileError(f"{self.fmu_path}: periodic clock {clock.name!r} has no interval "
                               "(the description gives none, nor does fmi3GetIntervalDecimal)")
        return known

    def _clock_update(self) -> None:
        """The FMU's intermediate update: read the countdown intervals and output clocks."""
        instance = self._require_instance()
        countdown = [c for c in self.clocks.clocks
                     if c.causality == "input" and c.interval_variability == "countdown"]
        if countdown:
            for clock, (interval, qualifier) in zip(
                    countdown, instance.intervals([c.value_reference for c in countdown]),
                    strict=True):
                if qualifier == INTERVAL_CHANGED:
                    self._push(clock, self._now + interval)
        outputs = [c for c in self.clocks.clocks if c.causality == "output"]
        if outputs:
            for clock, ticked in zip(outputs, instance.clocks([c.value_reference
                                                               for c in outputs]), strict=True):
                if ticked:
                    self._output_ticks.append(Tick(self._now, clock.name))

    def _variables_of(self, clock: int | None) -> list[_Variable]:
        """The outputs a tick of `clock` moves (None: every output)."""
        outputs = [v for v in self._variables if v.causality == "output"]
        if clock is None:
            return outputs
        return [v for v in outputs if clock in self.clocks.clocked_variables.get(v.name, ())
                or clock in self.clocks.dependencies.get(v.value_reference, ())]

    def _read(self, variables: list[_Variable]) -> dict[str, Any]:
        instance = self._require_instance()
        values: dict[str, Any] = {}
        for fmi_type in sorted({v.fmi_type for v in variables}):
            chosen = [v for v in variables if v.fmi_type == fmi_type]
            got = instance.get(fmi_type, [v.value_reference for v in chosen])
            values.update((v.name, value) for v, value in zip(chosen, got, strict=True))
        return values

    def _set_inputs(self) -> None:
        instance = self._require_instance()
        inputs = [v for v in self._variables if v.causality == "input"]
        for fmi_type in sorted({v.fmi_type for v in inputs}):
            chosen = [v for v in inputs if v.fmi_type == fmi_type]
            instance.set(fmi_type, [v.value_reference for v in chosen],
                         [self.inputs[v.name].get() for v in chosen])

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        for name, value in self._values.items():
            self.outputs[name].set(value, t)

    def _require_instance(self) -> ScheduledInstance:
        if self._instance is None:
            raise ConfigurationError(f"component {self.name!r} is not initialized")
        return self._instance

    def _release(self) -> None:
        if self._finalizer is not None:
            self._finalizer()
        self._instance, self._finalizer = None, None

    def free(self) -> None:
        """Terminate and free the instance and remove its extraction."""
        self._release()
        super().free()


def _weakly(method: weakref.WeakMethod) -> Callable[[], None]:
    """`method` called while its component lives: the instance's finalizer keeps the instance,
    which must not keep the component."""
    def call() -> None:
        bound = method()
        if bound is not None:
            bound()
    return call


def _free(instance: ScheduledInstance, unzip_dir: Path, key: Any) -> None:
    try:
        instance.free()
    finally:
        extractions.release(unzip_dir, key)


def _variable(variable: Any, path: Path) -> _Variable:
    if variable.type not in C_TYPES or variable.dimensions:
        raise FMUFileError(f"{path}: {variable.causality} {variable.name!r} is a "
                           f"{'array' if variable.dimensions else variable.type}: Scheduled "
                           "Execution components take scalar numeric and Boolean ports")
    return _Variable(variable.name, variable.valueReference, variable.type,
                     variable.causality)


def _parsed(text: str, kind: PortType) -> Any:
    if kind == PortType.BOOL:
        return text in ("true", "1")
    return int(text) if kind == PortType.INT else float(text)
