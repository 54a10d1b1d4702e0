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
input clock at its ticks. The engine does so in C (its Scheduled Execution component, built
from the plan's `scheduled_execution` and `scheduled_clock` records), with no Python per tick:

- periodic input clocks (intervalVariability constant, fixed, tunable, changing) tick at their
  shift and every interval after it (the description's, else the FMU's fmi3GetIntervalDecimal;
  a tunable or changing interval is asked again after each tick);
- triggered input clocks tick at the times given to `schedule_clock`;
- countdown clocks tick when the FMU announces their interval (its clockUpdate callback, then
  fmi3GetIntervalDecimal): at the announcing tick's time plus that interval;
- output clocks are read with fmi3GetClock in the clockUpdate callback; each tick is an own
  event of the component, so an EventConnection from it runs its handler there.

The step from t to t + dt activates, in order, every tick at or after t and before t + dt, so a
run from 0 to 10 s activates the ticks at 0 to 9 and the outputs at t + dt are those after the
step's ticks. Ticks at one instant run in priority order (the lowest `priority` value first,
then the lowest value reference), a countdown tick announced at that instant after the ones
due before it of higher priority: whatever the step size, the order is the same. The inputs are
set before each partition runs; after it, the outputs clocked by its clock or depending on it
(ModelStructure) are read, set on their ports and logged with the tick: `ticks` reads the
engine's log.
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..core.port import Port, PortSpec, PortType
from ..engine import ffi, lib
from ..errors import ConfigurationError, FMUFileError, SimulationError
from ..fmu.clocks import ClockInfo, ClockStructure
from ..fmu.description_fmi3 import clock_structure
from ..fmu.extraction import extractions
from ..fmu.info import PORT_TYPES
from ..fmu.standards import FMI3
from ..plan.fmu_records import FMI3_TYPES, FMULoad, ScheduledClock
from .base import CoSimComponent

if TYPE_CHECKING:
    from ..bridge.plan import EnginePlan

_PERIODIC = ("constant", "fixed", "tunable", "changing")
# ssx_scheduled_clock_kind
_PERIODIC_KIND, _TRIGGERED_KIND, _COUNTDOWN_KIND, _OUTPUT_KIND = 0, 1, 2, 3
# the FMI 3.0 types a port may have, by the word of their ssx_fmi3_type
_TYPE_WORDS = {"Float64": "float64", "Float32": "float32", "Int8": "int8", "UInt8": "uint8",
               "Int16": "int16", "UInt16": "uint16", "Int32": "int32", "UInt32": "uint32",
               "Int64": "int64", "UInt64": "uint64", "Boolean": "boolean",
               "Enumeration": "int64"}


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
        self._fmu: Any = None  # the engine's ssx_fmu, loaded with the first plan
        self._load_spec: FMULoad | None = None
        self._kept: list[Any] = []  # what the load spec points at
        self._finalizer: weakref.finalize | None = None
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
        if self._binding is not None:
            # the engine's times are the plan's: the next initialize builds a new one
            self._binding.plan.left = self.name

    def _clock(self, name: str) -> ClockInfo:
        try:
            return self.clocks.by_name(name)
        except KeyError as exc:
            raise ConfigurationError(f"component {self.name!r}: {exc.args[0]}") from None

    @property
    def output_clocks(self) -> list[str]:
        """The output clocks in the FMU's order; each tick is an own event, a source for an
        EventConnection."""
        return [c.name for c in self.clocks.clocks if c.causality == "output"]

    def _engine_clocks(self) -> list[ClockInfo]:
        """The clocks in the engine's order: the input clocks, then the output clocks."""
        clocks = self.clocks.clocks
        return [c for c in clocks if c.causality == "input"] + \
            [c for c in clocks if c.causality == "output"]

    def _scheduled(self, clock: ClockInfo) -> ScheduledClock:
        """A clock as the plan's scheduled_clock record gives it to the engine."""
        variability = clock.interval_variability
        kind = _OUTPUT_KIND if clock.causality == "output" else \
            _PERIODIC_KIND if variability in _PERIODIC else \
            _TRIGGERED_KIND if variability == "triggered" else _COUNTDOWN_KIND
        if kind == _PERIODIC_KIND and variability not in _PERIODIC:
            raise FMUFileError(f"{self.fmu_path}: input clock {clock.name!r} has "
                               f"intervalVariability {variability}, which no tick follows")
        period = clock.period if kind == _PERIODIC_KIND else None
        return ScheduledClock(
            kind, clock.value_reference, -1 if clock.priority is None else clock.priority,
            math.nan if period is None else float(period),
            float(clock.first_tick) if kind == _PERIODIC_KIND else 0.0,
            kind == _PERIODIC_KIND and variability in ("tunable", "changing"),
            tuple(self._triggered_times.get(clock.name, ())) if kind == _TRIGGERED_KIND
            else (),
            () if kind == _OUTPUT_KIND else
            tuple(v.name for v in self._moved_by(clock.value_reference)))

    def _moved_by(self, clock: int) -> list[_Variable]:
        """The outputs a tick of `clock` moves: clocked by it or depending on it."""
        return [v for v in self._variables if v.causality == "output"
                and (clock in self.clocks.clocked_variables.get(v.name, ())
                     or clock in self.clocks.dependencies.get(v.value_reference, ()))]

    # ------------------------------------------------------------------ the engine
    def _make_port(self, spec: PortSpec) -> Port:
        if spec.direction == "out":
            return Port(spec, reader=lambda n=spec.name: self._engine_output(n))
        return Port(spec)

    def _engine_output(self, name: str) -> float | int | bool:
        """The engine's value of an output (0 before the component runs in a system)."""
        value = 0.0 if self._binding is None else \
            self._binding.plan.port_value(self, "out", name)
        return _typed(self.output_specs[name].type, value)

    def _value_reference(self, name: str) -> int:
        return next(v.value_reference for v in self._variables if v.name == name)

    def _load(self) -> tuple[Any, FMULoad]:
        """The FMU's binary loaded into the engine as Scheduled Execution (once)."""
        if self._fmu is not None and self._load_spec is not None:
            return self._fmu, self._load_spec
        unzip_dir, key = extractions.acquire(self.fmu_path, shareable=False)
        binary = extractions.binary(unzip_dir, FMI3().binary_name(self._identifier))
        if binary is None:
            extractions.release(unzip_dir, key)
            raise FMUFileError(f"{self.fmu_path}: {FMI3().binary_name(self._identifier)} is "
                               "not a file inside the extracted archive")
        table, kept = self._type_table()
        texts = [ffi.new("char[]", text.encode()) for text in (
            str(binary), self._identifier, self._token, f"{unzip_dir / 'resources'}/",
            self.name)]
        spec = ffi.new("ssx_fmu_load_spec *", {
            "version": 3, "interface": lib().SSX_SCHEDULED_EXECUTION, "binary_path": texts[0],
            "model_identifier": texts[1], "guid": texts[2], "resource_location": texts[3],
            "instance_name": texts[4], "fmi3_variables": table})
        error = ffi.new("char[1024]")
        fmu = lib().ssx_fmu_load(spec, error, 1024)
        if fmu == ffi.NULL:
            extractions.release(unzip_dir, key)
            raise FMUFileError(f"{self.fmu_path}: cannot load "
                               f"{FMI3().binary_name(self._identifier)}: "
                               f"{ffi.string(error).decode(errors='replace')}")
        self._fmu, self._kept = fmu, [table, kept]
        # resolved now: a finalizer must not be the first to look up a library function
        self._finalizer = weakref.finalize(self, _free, lib().ssx_fmu_free, fmu, unzip_dir, key)
        self._load_spec = FMULoad(3, str(unzip_dir), self._identifier, self._token, self.name,
                                  table)
        return fmu, self._load_spec

    def _type_table(self) -> tuple[Any, list[Any]]:
        """The load spec's ssx_fmi3_variables: the ports' variables, the output clocks and the
        countdown clocks (in description order), and what it points at."""
        names = [ffi.new("char[]", v.name.encode()) for v in self._variables]
        output_clocks = [c.value_reference for c in self.clocks.clocks
                         if c.causality == "output"]
        countdown = [c.value_reference for c in self.clocks.clocks
                     if c.causality == "input" and c.interval_variability == "countdown"]
        arrays = [ffi.new("unsigned int[]", [v.value_reference for v in self._variables]),
                  ffi.new("unsigned char[]", [FMI3_TYPES.index(_TYPE_WORDS[v.fmi_type])
                                              for v in self._variables]),
                  ffi.new("char *[]", names),
                  ffi.new("unsigned int[]", output_clocks or [0]),
                  ffi.new("unsigned int[]", countdown or [0])]
        table = ffi.new("ssx_fmi3_variables *", {
            "vr": arrays[0], "type": arrays[1], "name": arrays[2], "n": len(self._variables),
            "output_clock_vr": arrays[3] if output_clocks else ffi.NULL,
            "n_output_clocks": len(output_clocks),
            "countdown_clock_vr": arrays[4] if countdown else ffi.NULL,
            "n_countdown_clocks": len(countdown)})
        return table, [names, arrays]

    def _add_to_plan(self, plan: EnginePlan) -> None:
        fmu, load = self._load()
        plan.add_scheduled_component(self, fmu, load, self._value_reference,
                                     [self._scheduled(c) for c in self._engine_clocks()])

    def _start(self, t0: float, tolerance: float | None = None) -> None:
        """The instance made and in initialization mode at t0: the System's initialize makes
        it leave, reads its outputs and plans the first ticks."""
        self._sync_ports()
        self.t = t0
        fmu, _ = self._load()
        experiment = ffi.new("ssx_fmu_experiment *", {"start_time": t0})
        status = lib().ssx_fmu_enter_initialization(fmu, experiment, ffi.NULL, ffi.NULL,
                                                    ffi.NULL)
        if status not in (0, 1):
            call = ffi.string(lib().ssx_fmu_last_call(fmu)).decode(errors="replace")
            log = ffi.string(lib().ssx_fmu_last_message(fmu)).decode(errors="replace")
            raise SimulationError(f"{self.name}: {call} failed at t={t0:g}"
                                  + (f" ({log})" if log else ""), component=self.name,
                                  time=t0)
        self._set_event_ports(t0, None)

    def can_rollback(self) -> bool:
        return False  # a Scheduled Execution FMU has no FMU state

    @property
    def ticks(self) -> list[Tick]:
        """Every tick of the last run in order, read from the engine's log (none before the
        component runs in a system)."""
        if self._binding is None:
            return []
        plan = self._binding.plan
        index = plan.index[self.name]
        count = ffi.new("size_t *")
        n = int(lib().ssx_scheduled_tick_count(plan.sys, index, count))
        n_values = int(count[0])
        times, clocks = ffi.new("double[]", n or 1), ffi.new("int[]", n or 1)
        first = ffi.new("size_t[]", n + 1)
        outputs, values = ffi.new("int[]", n_values or 1), ffi.new("double[]", n_values or 1)
        plan.check(lib().ssx_scheduled_ticks(plan.sys, index, times, clocks, first, outputs,
                                             values), self.name)
        clock_names = [c.name for c in self._engine_clocks()]
        ports = plan.outputs[self.name]
        return [Tick(float(times[k]), clock_names[clocks[k]], {
            ports[outputs[i]]: _typed(self.output_specs[ports[outputs[i]]].type, values[i])
            for i in range(first[k], first[k + 1])}) for k in range(n)]

    def free(self) -> None:
        """Free the engine's instance and binary and remove its extraction."""
        if self._finalizer is not None:
            self._finalizer()
        self._fmu, self._load_spec, self._finalizer = None, None, None
        super().free()


def _free(free_fmu: Any, fmu: Any, unzip_dir: Path, key: Any) -> None:
    """The finalizer: `free_fmu` is ssx_fmu_free, looked up when the FMU was loaded."""
    try:
        free_fmu(fmu)
    finally:
        extractions.release(unzip_dir, key)


def _variable(variable: Any, path: Path) -> _Variable:
    if variable.type not in _TYPE_WORDS or variable.dimensions:
        raise FMUFileError(f"{path}: {variable.causality} {variable.name!r} is a "
                           f"{'array' if variable.dimensions else variable.type}: Scheduled "
                           "Execution components take scalar numeric and Boolean ports")
    return _Variable(variable.name, variable.valueReference, variable.type,
                     variable.causality)


def _typed(kind: PortType, value: float) -> float | int | bool:
    return int(value) if kind == PortType.INT else bool(value) if kind == PortType.BOOL \
        else float(value)


def _parsed(text: str, kind: PortType) -> Any:
    if kind == PortType.BOOL:
        return text in ("true", "1")
    return int(text) if kind == PortType.INT else float(text)
