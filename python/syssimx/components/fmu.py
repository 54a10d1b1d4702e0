"""FMUComponent: an FMI 2.0 FMU stepped by the engine, through its Co-Simulation interface
(fmi2DoStep) or its Model Exchange interface (integrated by the engine with CVODE), and the
same for an FMI 3.0 and an FMI 1.0 FMU (syssimx.fmu reads the archive and decides the
version; an FMI 1.0 FMU has no FMU state, so it cannot be rolled back).

Plain use costs no Python per step: the engine calls the FMU directly, rolls it back with
fmi2Get/SetFMUstate for event localization and evaluates variable indicators in C. Overriding
a hook (`_do_step_internal`, `_update_output_states`, `snapshot_state`/`restore_state`,
`_handle_events_internal`, `_record_outputs`) routes that hook through Python.

By default the FMU's binary runs inside this process, like any library: a crash in it ends
Python. `isolated=True` runs it in a host process of its own (every fmi2 call crosses a
socket), so a crash, an abort or, with `step_timeout`, a hang becomes a SimulationError.

Like FMPy, syssimx writes to the FMU only the values the user set (parameters, inputs); the
FMU keeps its own defaults otherwise, even where the modelDescription declares a rounded copy
of them. fmi2SetupExperiment gets the tolerance the user gave (to the component, else to
System.initialize), else the DefaultExperiment's; a Model Exchange component integrates with
that relative tolerance (absolute: times each state's nominal), else the engine's default.

An FMI 3.0 Co-Simulation FMU is instantiated with event mode when it declares hasEventMode,
and with early return when it can return early: it then handles its own events inside the
engine's step, at their time, without rollback (they appear in the result's events as its own),
as a Model Exchange FMU of either version does inside its integration. Its Float32 and
integer types travel as Real and Integer ports. String inputs and outputs (every version) and
FMI 3.0 Binary ones are ports whose values are texts or bytes: connected to ports of their
type, recorded as object arrays; String and Binary parameters are set with set_parameters
(inputs too) and read with get_state.
"""

from __future__ import annotations

import copy
import math
import weakref
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .. import units
from ..core.element_map import made_items
from ..core.port import TABLED_TYPES, Port, PortSpec, PortType
from ..core.suggest import did_you_mean
from ..engine import lib
from ..errors import ConfigurationError, FMUError
from ..fmu.description_fmi3 import output_clocks, triggered_input_clocks
from ..fmu.extraction import extractions
from ..fmu.info import (
    INTERFACES,
    PORT_TYPES,
    FMUInfo,
    FMUInterface,
    Parameter,
    read_fmu,
    variable_unit,
)
from ..fmu.instance import FMUInstance, start_values
from ..fmu.loading import load
from ..fmu.variable_table import VariableTable
from ..plan.fmu_records import FMULoad
from ..plan.records import PlanRecords, value_type_word
from ..units import is_quantity, magnitude_in
from .base import CoSimComponent, _overrides
from .fmu_display import component_html, component_text
from .restart import Reinitialize, Term

if TYPE_CHECKING:
    from ..bridge.plan import EnginePlan


class FMUComponent(CoSimComponent):
    """An FMI 1.0 or 2.0 FMU (linux64 binary) or an FMI 3.0 FMU (x86_64-linux) as a
    component."""

    def __init__(self, name: str, fmu_path: str | Path, group: str | None = None,
                 tolerance: float | None = None, *, isolated: bool = False,
                 step_timeout: float | None = None, interface: str = "auto") -> None:
        """
        Args:
            name: the component's name in its system.
            fmu_path: the .fmu archive.
            group: SysSimX's component group, kept as `group` (syssimx does not use it).
            tolerance: the relative tolerance for fmi2SetupExperiment (and the engine's
                integrator under Model Exchange).
            isolated: run the binary in a process of its own.
            step_timeout: seconds (needs isolation): an fmi2 call that takes longer kills that
                process and fails the run.
            interface: "co-simulation", "model-exchange" or "auto" (Co-Simulation when the FMU
                has it, else Model Exchange).
        """
        if step_timeout is not None and not isolated:
            raise ConfigurationError(f"component {name!r}: step_timeout needs isolated=True "
                                     "(a hung FMU inside this process cannot be stopped)")
        if step_timeout is not None and not step_timeout > 0:
            raise ConfigurationError(f"component {name!r}: step_timeout must be a positive "
                                     f"number of seconds, got {step_timeout!r}")
        super().__init__(name, group=group)
        self.isolated = isolated
        self.step_timeout = step_timeout
        self.info: FMUInfo = read_fmu(fmu_path)
        self.fmu_path = str(self.info.path)
        if isolated and not self.info.standard.isolatable:
            raise ConfigurationError(f"component {name!r}: isolated=True is not supported for "
                                     f"{self.info.standard.name} FMUs ({self.fmu_path}): the "
                                     "FMU host process speaks FMI 2.0 and FMI 1.0 "
                                     "Co-Simulation only")
        self.fmu_interface: FMUInterface = _chosen_interface(self.info, name, interface)
        if isolated and self.model_exchange:
            raise ConfigurationError(
                f"component {name!r}: isolated=True runs an FMU's Co-Simulation interface "
                f"only, and {self.info.path.name} runs as Model Exchange here (the engine "
                "integrates it in this process); drop isolated=True"
                + (' or pass interface="co-simulation"'
                   if "co-simulation" in self.info.interfaces else ""))
        # the relative tolerance for fmi2SetupExperiment; None: System.initialize's, else the
        # DefaultExperiment's
        self.tolerance = _checked_tolerance(tolerance, f"{name}: tolerance")
        self._experiment_tolerance = _first_given(self.tolerance, self.info.default_tolerance)
        # an FMI 3.0 array's elements get their spec, port, start and parameter value when
        # they are asked for (ElementMap), a scalar's at once
        self.input_specs = self.info.input_specs.copy()
        self.output_specs = self.info.output_specs.copy()
        self.direct_feedthrough = self.info.feedthrough.mapped(lambda _, inputs: set(inputs))
        self._declared_outputs: set[str] = set()  # by declare_dependencies
        self.parameters = self.info.parameters.mapped(lambda _, parameter: parameter.start)
        self._declared_parameters = self.parameters.copy()
        self._parameters_set: set[str] = set()  # named in set_parameters: written even if equal
        self._input_starts = self.info.input_starts.copy()  # set_inputs changes the copy
        if isolated:
            self._drop_text_ports()
        self.inputs = self.input_specs.mapped(lambda _, spec: self._make_port(spec))
        self.outputs = self.output_specs.mapped(lambda _, spec: self._make_port(spec))
        self._inputs_set: set[str] = set()
        # String or Binary parameters (arrays are never String ones): the engine writes
        # numbers only
        self._has_text_parameters = any(parameter.type == PortType.STRING for parameter
                                        in made_items(self.info.parameters).values())
        # name -> (value type, value reference) of what _by_type wrote so far
        self._written_variables: dict[str, tuple[PortType, int]] = {}
        # the FMI 3.0 type table the plan writes (and what it points at), made once
        self._fmi3_table: tuple[Any, Any] | None = None
        fmu, self._unzip_dir, extraction_key = load(self.info, self.fmu_interface, name,
                                                    isolated, step_timeout)
        self.instance = FMUInstance(fmu, name, self.info.standard.function_prefix)
        # resolved now: a finalizer must not be the first to look up a library function
        self._finalizer = weakref.finalize(self, _release, lib().ssx_fmu_free, self.instance,
                                           self._unzip_dir, extraction_key)
        self._sync_ports()

    def __repr__(self) -> str:
        return component_text(self)

    def _repr_html_(self) -> str:
        return component_html(self)

    def undeclared_outputs(self) -> set[str]:
        """The outputs whose dependencies the FMU's ModelStructure does not declare (an
        array's elements when the array's are not), unless declare_dependencies gave them."""
        undeclared = self.info.undeclared_outputs
        return {name for name in self.feedthrough() if name not in self._declared_outputs
                and (name in undeclared or name.split("[", 1)[0] in undeclared)}

    def declare_dependencies(self, **outputs: Iterable[str]) -> None:
        """The inputs each named output depends on directly, for an FMU whose ModelStructure
        declares none (by the standard, every input): ``declare_dependencies(force=[])``."""
        for output, inputs in outputs.items():
            if output not in self.output_specs:
                raise ConfigurationError(f"{self.name}: no output {output!r} to declare "
                                         f"dependencies of; outputs: {sorted(self.output_specs)}")
            names = [inputs] if isinstance(inputs, str) else list(inputs)
            unknown = [name for name in names if name not in self.input_specs]
            if unknown:
                raise ConfigurationError(f"{self.name}.{output}: no input(s) {unknown}; inputs: "
                                         f"{sorted(self.input_specs)}")
            self.direct_feedthrough[output] = set(names)
            self._declared_outputs.add(output)

    def _drop_text_ports(self) -> None:
        """The host process that runs an FMU apart forwards no String calls: its String
        inputs and outputs are no ports (arrays are never String ones)."""
        for specs in (self.input_specs, self.output_specs):
            for name in [n for n, s in made_items(specs).items() if s.type in TABLED_TYPES]:
                del specs[name]
                self.direct_feedthrough.pop(name, None)
        for inputs in self.direct_feedthrough.values():
            inputs.intersection_update(self.input_specs)

    @property
    def _fmu(self) -> Any:
        """The engine's ssx_fmu (FMUError after free())."""
        return self.instance.fmu

    @property
    def _instance(self) -> FMUInstance:
        """SysSimX's name of the instance proxy."""
        return self.instance

    @property
    def can_get_set_state(self) -> bool:
        """Whether the FMU declares canGetAndSetFMUstate (its own state save and restore)."""
        return self.fmu_interface.can_get_set_state

    @property
    def model_exchange(self) -> bool:
        """Whether the engine integrates the FMU (its Model Exchange interface)."""
        return self.fmu_interface.name == "model-exchange"

    @property
    def output_clocks(self) -> list[str]:
        """The FMI 3.0 output clocks the engine reads in Co-Simulation, in its order; each is
        an event source for an EventConnection."""
        return [] if self.model_exchange else \
            [c.name for c in output_clocks(self.info.clocks.clocks)]

    @property
    def triggered_clocks(self) -> list[str]:
        """The FMI 3.0 triggered input clocks the engine ticks in Co-Simulation, in its order;
        an EventConnection from an indicator or an output clock to one ticks it."""
        return [] if self.model_exchange else \
            [c.name for c in triggered_input_clocks(self.info.clocks.clocks)]

    # ---------------------------------------------------------------- ports
    def _make_port(self, spec: PortSpec) -> Port:
        if spec.type == PortType.EVENT:
            return Port(spec)
        if spec.direction == "out":
            return Port(spec, reader=lambda n=spec.name: self._engine_value("out", n))
        return Port(spec, self._input_starts.get(spec.name),
                    reader=lambda n=spec.name: self._engine_value("in", n))

    def _engine_value(self, direction: str, name: str) -> float | int | bool | str:
        """The engine's current value of a port. Before the component runs in a system, an
        input reads its start value and an output 0 ("" a String one: the FMU computes it at
        initialization)."""
        kind = (self.output_specs if direction == "out" else self.input_specs)[name].type
        if self._binding is None:
            return self._input_starts[name] if direction == "in" else \
                "" if kind == PortType.STRING else b"" if kind == PortType.BINARY else 0.0
        value = self._binding.plan.port_value(self, direction, name)
        if math.isnan(value) and direction == "in":
            return self._input_starts[name]  # not yet read from the FMU (see input_start)
        if kind in TABLED_TYPES:
            return self._binding.plan.from_engine(kind, value)
        return int(value) if kind == PortType.INT else bool(value) if kind == PortType.BOOL \
            else value

    def why_no_port(self, name: str) -> str:
        """A name several variables have is ambiguous; String and Binary parameters are
        values, never ports."""
        references = self.info.ambiguous_names.get(name)
        if references is not None:
            return (f" (the FMU names {len(references)} variables {name!r}, value references "
                    f"{', '.join(map(str, references))}: the name is ambiguous)")
        parameter = self.info.parameters.get(name)
        kind = parameter.fmi_type if parameter is not None else ""
        if kind not in ("String", "Binary"):
            return ""
        return (f" (it is a {kind} variable: set it with set_parameters, read it with "
                "get_state; it cannot be connected)")

    def input_start(self, name: str) -> float | str | bytes:
        """What set_inputs gave (a String input's text, a Binary one's bytes), else NaN: the
        engine then keeps the FMU's own value."""
        if name not in self._inputs_set:
            return math.nan
        start = self._input_starts[name]
        return start if isinstance(start, str | bytes) else float(start)

    def value_reference(self, name: str) -> int:
        """The FMU's value reference of the variable `name`."""
        known = self.info.value_references.get(name)
        return int(self.info.variables[name].valueReference) if known is None else known

    def _indicator_slope(self, name: str) -> int | None:
        """The value reference of the variable this Co-Simulation FMU declares the time
        derivative of the variable `name` (the `derivative` attribute of a Real, FMI 2.0, or of
        a scalar Float64, FMI 3.0), or None. Event localization on `name` aims from it."""
        variables = self.info.description.modelVariables
        if self.model_exchange:
            return None
        if isinstance(variables, VariableTable):
            derivative = variables.derivative_of(variables.find(name))
            return int(variables[derivative].valueReference) if derivative >= 0 else None
        for variable in variables:  # fmpy's objects: the derivative names the variable
            of = getattr(variable, "derivative", None)
            if of is not None and getattr(of, "name", None) == name and \
                    variable.type == "Float64" and not getattr(variable, "dimensions", None):
                return int(variable.valueReference)
        return None

    def set_inputs(self, signals: dict[str, Any], t: float | None = None) -> None:
        """Set inputs; they go to a Co-Simulation FMU at once when it is instantiated."""
        for name, value in signals.items():
            if name not in self.input_specs:
                raise ConfigurationError(f"component {self.name!r} has no input {name!r}"
                                         f"{did_you_mean(name, self.input_specs)}; "
                                         f"inputs: {sorted(self.input_specs) or 'none'}")
            self._input_starts[name] = self.input_specs[name].coerce(value)
            self._inputs_set.add(name)
        if self._binding is not None:
            self._binding.plan.write_inputs(self, signals)
        # the engine writes a Model Exchange FMU's inputs in event mode, where discrete ones
        # may change, before its next step
        if self.instance.alive() and not self.model_exchange:
            self._write_to_fmu({n: self._input_starts[n] for n in signals})

    def _write_to_fmu(self, values: dict[str, Any]) -> None:
        setters = {PortType.REAL: self.instance.setReal, PortType.INT: self.instance.setInteger,
                   PortType.BOOL: self.instance.setBoolean}
        for kind, (refs, vals) in self._by_type(values).items():
            setters[kind](refs, vals)
        self._write_texts(values)

    def _write_texts(self, values: dict[str, Any]) -> None:
        """The String and Binary parameters among `values`."""
        setters = {"String": self.instance.setString, "Binary": self.instance.setBinary}
        for name, value in values.items():
            parameter = self.info.parameters.get(name)
            if parameter is not None and parameter.fmi_type in setters:
                setters[parameter.fmi_type]([parameter.value_reference], [value])

    def _by_type(self, values: dict[str, Any]) -> dict[PortType, tuple[list[int], list[Any]]]:
        """Value references and values of parameters and inputs, grouped by value type (String
        and Binary ones are written by _write_texts)."""
        by_type: dict[PortType, tuple[list[int], list[Any]]] = {}
        written = self._written_variables
        for name, value in values.items():
            known = written.get(name)
            if known is None:
                known = written[name] = self._written_variable(name)
            kind, reference = known
            if kind in TABLED_TYPES:
                continue
            if kind == PortType.INT and not INT_MIN <= value <= INT_MAX:
                raise ConfigurationError(f"{self.name}.{name}: {value} is outside the range of "
                                         f"the engine's Integer ports ({INT_MIN}..{INT_MAX})")
            refs, vals = by_type.setdefault(kind, ([], []))
            refs.append(reference)
            vals.append(value)
        return by_type

    def _written_variable(self, name: str) -> tuple[PortType, int]:
        """The value type and value reference of a parameter or input written to the FMU
        (fixed by its modelDescription: _by_type keeps them, looked up once per name)."""
        kind = self.input_specs[name].type if name in self.input_specs \
            else self.info.parameters[name].type
        return kind, -1 if kind in TABLED_TYPES else self.value_reference(name)

    # ---------------------------------------------------------------- parameters
    def set_parameters(self, **parameters: Any) -> None:
        """Numbers or pint quantities (converted to the FMU's unit). They are written to the
        FMU at initialize (and reinitialize): set on a running FMU they wait for the next one
        (the next run without it warns), as start values do in SysSimX and FMPy."""
        if self._binding is not None and parameters and self.instance.mode == "step":
            waiting = self._binding.plan.waiting_parameters
            waiting[self.name] = tuple(dict.fromkeys((*waiting.get(self.name, ()), *parameters)))
        for name, value in parameters.items():
            parameter = self.info.parameters.get(name)
            sized = self.info.structural_parameters.get(name) if parameter is None else None
            if sized is not None:
                raise ConfigurationError(
                    f"component {self.name!r}: {name!r} is a structural parameter (it sizes "
                    f"the array(s) {', '.join(map(repr, sized))}); syssimx keeps its start "
                    f"value {self.info.variables[name].start}: changing it is not supported")
            if parameter is None:
                raise ConfigurationError(
                    f"component {self.name!r} has no parameter {name!r}"
                    f"{self.why_no_port(name) or did_you_mean(name, self.info.parameters)}; "
                    f"known parameters: {sorted(self.info.parameters) or 'none'}")
            self.parameters[name] = _coerce_parameter(self.name, parameter, value)
            self._parameters_set.add(name)

    def user_parameters(self) -> dict[str, Any]:
        """The parameters the user set: named in set_parameters (or reinitialize), or changed
        in `parameters`. Only these are written to the FMU."""
        declared, named = self._declared_parameters, self._parameters_set
        made = made_items(declared)  # a dict's lookups, an ElementMap's only for the rest
        return {n: v for n, v in made_items(self.parameters).items()
                if v is not None and (n in named or v != (made[n] if n in made
                                                          else declared.get(n)))}

    def _apply_parameters_starts(self) -> None:
        """Write the parameters the user set to the FMU. In step mode only tunable ones (FMI
        forbids setting fixed parameters after initialization)."""
        self._write_to_fmu(self._parameter_starts(step_mode=self.instance.mode == "step"))
        if self._binding is not None and self.instance.mode != "step":
            self._binding.plan.waiting_parameters.pop(self.name, None)

    def _apply_input_starts(self) -> None:
        """Write the inputs the user set to the FMU; in a system, the engine's current input
        values (connections drive them; an input never set holds the FMU's own value there,
        NaN before the engine read it)."""
        self._write_to_fmu(self._input_starts_to_write())

    def _parameter_starts(self, step_mode: bool) -> dict[str, Any]:
        if not step_mode:
            return self.user_parameters()
        return {n: v for n, v in self.user_parameters().items()
                if self.info.parameters[n].tunable}

    def _input_starts_to_write(self) -> dict[str, Any]:
        if self._binding is None:
            return {n: self._input_starts[n] for n in self._inputs_set}
        plan = self._binding.plan
        names = plan.inputs[self.name]
        if not names:
            return {}
        engine = plan.input_array(self)
        return {n: plan.from_engine(kind, engine[i]) if kind in TABLED_TYPES
                else _typed_input(kind, engine[i])
                for i, n in enumerate(names) if not math.isnan(engine[i])
                for kind in (self.input_specs[n].type,)}

    def _start_hooks_overridden(self) -> bool:
        """Whether a subclass writes the start values itself (SysSimX's hooks)."""
        cls = type(self)
        return (cls._apply_parameters_starts is not FMUComponent._apply_parameters_starts
                or cls._apply_input_starts is not FMUComponent._apply_input_starts)

    def _apply_starts(self) -> None:
        self._apply_parameters_starts()
        self._apply_input_starts()

    # ---------------------------------------------------------------- life cycle
    def _start(self, t0: float, tolerance: float | None = None) -> None:
        self._sync_ports()
        self.t = t0
        system_tolerance = None if tolerance is None else _checked_tolerance(
            tolerance, f"{self.name}: the tolerance given to System.initialize")
        self._experiment_tolerance = _first_given(self.tolerance, system_tolerance,
                                                  self.info.default_tolerance)
        if type(self).reinitialize is FMUComponent.reinitialize and self._binding is not None:
            # the System's initialize gives the instance its connected inputs in
            # initialization mode and makes it leave (the initial-value problem)
            self._reinitialize(t0, {}, system_exits=True)
        else:
            self.reinitialize(t0)
        self._set_event_ports(t0, None)
        self._set_engine_restart()

    def reinitialize(self, t: float, **start_values: Any) -> None:
        """Fresh instance at time t (one engine call): instantiate, setupExperiment(t),
        initialization mode with the parameters and inputs the user set written (by
        `_apply_parameters_starts`/`_apply_input_starts` when a subclass overrides them),
        exit. `start_values` (parameters, numbers or pint quantities) override `parameters`
        for this instance only, so a later System.initialize starts from the parameters the
        user set."""
        self._reinitialize(t, start_values, system_exits=False)

    def _reinitialize(self, t: float, start_values: dict[str, Any], system_exits: bool) -> None:
        """reinitialize; system_exits: the instance stays in initialization mode for the
        System's initialize to make it leave (its outputs are read then)."""
        saved, saved_set = self.parameters, self._parameters_set
        overrides = {}
        for name, value in start_values.items():
            if name not in self.info.parameters:
                raise ConfigurationError(
                    f"component {self.name!r} has no parameter {name!r}"
                    f"{did_you_mean(name, self.info.parameters)}; "
                    f"known parameters: {sorted(self.info.parameters)}")
            overrides[name] = _coerce_parameter(self.name, self.info.parameters[name], value)
        if overrides or self._start_hooks_overridden():
            # on copies: neither the overrides nor what a subclass's hooks change stay
            self.parameters = copy.copy(saved)
            self.parameters.update(overrides)
            self._parameters_set = saved_set | set(overrides)
            try:
                self._initialize_instance(t, system_exits)
            finally:
                self.parameters, self._parameters_set = saved, saved_set
        else:
            self._initialize_instance(t, system_exits)
        self.t = t
        if self._binding is not None:
            self._binding.plan.waiting_parameters.pop(self.name, None)
            if not system_exits:
                self._binding.plan.read_outputs(self)

    def _initialize_instance(self, t: float, system_exits: bool = False) -> None:
        """The instance ready to step at t with the parameters and inputs the user set: the
        engine writes the values itself (one call) unless a subclass's hooks do."""
        if self._start_hooks_overridden():
            self.instance.initialize(t, self._experiment_tolerance,
                                     in_initialization_mode=self._apply_starts,
                                     system_exits=system_exits)
            return
        starts = self._initialization_starts(system_exits)
        texts = {n: v for n, v in starts.items()
                 if n in self.info.parameters
                 and self.info.parameters[n].type == PortType.STRING} \
            if self._has_text_parameters else None
        self.instance.initialize(
            t, self._experiment_tolerance, self._by_type(starts),
            in_initialization_mode=(lambda: self._write_texts(texts)) if texts else None,
            system_exits=system_exits)

    def _initialization_starts(self, system_exits: bool) -> dict[str, Any]:
        """What initialization mode writes: every parameter the user set (the FMU is in
        initialization mode), then the inputs the user set; with system_exits not those the
        engine gives their connected values at t0."""
        starts = self.user_parameters()
        inputs = self._input_starts_to_write()
        if system_exits:
            driven = self._binding.plan.driven  # type: ignore[union-attr]
            inputs = {n: v for n, v in inputs.items() if (self.name, n) not in driven}
        starts.update(inputs)
        return starts

    def _add_to_plan(self, plan: EnginePlan) -> None:
        """The engine steps the FMU itself; only what a subclass overrides runs in Python. An
        FMU that may be instantiated only once per process keeps globals in its binary and
        steps on the calling thread, unless its binary runs in a host process of its own."""
        model_exchange = (self.info.number_of_states, self.info.number_of_event_indicators) \
            if self.model_exchange else None
        once_per_process = self.fmu_interface.can_be_instantiated_only_once_per_process
        interface = self.fmu_interface
        # an isolated FMU's host forwards neither input nor output derivatives
        direct = not self.isolated and not self.model_exchange
        output_order = interface.max_output_derivative_order if direct else 0
        if str(self.info.description.fmiVersion).startswith("3.") and \
                any(self.info.feedthrough.values()):
            # FMI 3.0 gives an FMU no input derivatives: the derivative of an output that
            # depends directly on inputs misses their motion (the coupling history serves)
            output_order = 0
        plan.add_fmu_component(
            self, self._fmu, self._load(), self.can_get_set_state,
            interface.provides_directional_derivative,
            self.value_reference, self._python_hooks(engine_steps=True), model_exchange,
            calling_thread_only=once_per_process and not self.isolated,
            interpolation=(direct and interface.can_interpolate_inputs, output_order))

    def _load(self) -> FMULoad:
        """How the FMU's binary was loaded, for the plan (the type table stays alive as long
        as the component)."""
        interface = self.fmu_interface
        if self._fmi3_table is None:
            self._fmi3_table = self.info.standard.engine_variables(self.info, interface)
        return FMULoad(self.info.standard.engine_version, str(self._unzip_dir),
                       interface.model_identifier, self.info.description.guid or "", self.name,
                       self._fmi3_table[0], self.isolated, self.step_timeout or 0.0)

    def _python_hooks(self, engine_steps: bool) -> set[str]:
        """A handler the engine runs (an engine restart) needs no Python hook."""
        hooks = super()._python_hooks(engine_steps)
        if self._engine_restart() is not None:
            hooks.discard("handle_events")
        return hooks

    def _engine_restart(self) -> dict[str, Term] | None:
        """The terms of the Reinitialize the engine runs for this component's events, or None
        where Python must handle them: a class of the user's that overrides how events or
        starts are handled, several handlers or EVENT inputs, an event that arrives elsewhere,
        a value for a parameter that is not Real, an FMU with String or Binary parameters (the
        engine writes numbers only). Decided by what the plan is compiled from, so it holds
        for every initialize on that plan."""
        if not self.event_handlers:
            return None
        handlers = [h for port in self.event_handlers.values() for h in port]
        if len(handlers) != 1 or not isinstance(handlers[0], Reinitialize) \
                or any(_overrides(self, hook) for hook in _EVENT_HOOKS):
            return None
        (port,) = (p for p, found in self.event_handlers.items() if found)
        if any(routes != {port} for routes in self._event_routes.values()):
            return None
        terms = handlers[0].terms(self)
        if any(self.info.parameters[p].type != PortType.REAL for p in terms) \
                or self._has_text_parameters:
            return None
        return terms

    def _restart_values(self) -> tuple[dict[PortType, tuple[list[int], list[Any]]],
                                       list[tuple[int, int, float]]] | None:
        """The engine's restart of this initialize, or None: the start values the user set
        and the constant terms among them, by type, and (value reference, output, gain) of
        each term read from the outputs at the event."""
        terms = self._engine_restart()
        binding = self._binding
        if terms is None or binding is None:
            return None
        from_outputs = {p: t for p, t in terms.items() if t.output is not None}
        starts = {n: v for n, v in self._parameter_starts(step_mode=False).items()
                  if n not in from_outputs}
        starts.update({p: t.gain for p, t in terms.items() if t.output is None})
        outputs = binding.plan.outputs[self.name]
        return self._by_type(starts), [(self.value_reference(p), outputs.index(t.output), t.gain)
                                       for p, t in from_outputs.items()
                                       if t.output is not None]

    def _set_engine_restart(self) -> None:
        """Hand the engine this initialize's restart."""
        restart = self._restart_values()
        if restart is None or self._binding is None:
            return
        starts, terms = restart
        values, _arrays = start_values(starts)  # alive until the engine copied them
        self._binding.plan.set_restart(self, self._experiment_tolerance, values,
                                       [vr for vr, _, _ in terms],
                                       [output for _, output, _ in terms],
                                       [gain for _, _, gain in terms])

    def _plan_initialization(self, index: int) -> PlanRecords:
        """The records that initialize this FMU (component `index`) as System.initialize
        does: its experiment, the parameters the user set, its engine restart."""
        records = PlanRecords()
        tolerance = self._experiment_tolerance
        records.add("fmu_experiment", index, tolerance is not None, float(tolerance or 0.0),
                    False, 0.0, about=self.name)
        parameters = self.user_parameters()
        for kind, (references, values) in self._by_type(parameters).items():
            for reference, value in zip(references, values, strict=True):
                records.add("start", index, value_type_word(kind), reference, float(value),
                            about=self.name)
        for name, value in parameters.items():
            parameter = self.info.parameters.get(name)
            if parameter is not None and parameter.fmi_type in ("String", "Binary"):
                records.add("start", index, value_type_word(parameter.type),
                            parameter.value_reference, value, about=f"{self.name}.{name}")
        restart = self._restart_values()
        if restart is not None:
            starts, terms = restart
            empty: tuple[list[int], list[Any]] = ([], [])
            records.add("restart_handler", index, tolerance is not None,
                        float(tolerance or 0.0), False, 0.0,
                        *([(vr, convert(v)) for vr, v in zip(*starts.get(kind, empty),
                                                               strict=True)]
                          for kind, convert in ((PortType.REAL, float), (PortType.INT, int),
                                                (PortType.BOOL, bool))),
                        [(vr, output, float(gain), 0.0) for vr, output, gain in terms],
                        about=f"{self.name}: event handler")
        return records

    # ---------------------------------------------------------------- hooks (engine built-ins)
    def _do_step_internal(self, t: float, dt: float) -> None:
        """One doStep of the FMU from t to t + dt, inputs written first, outputs read after."""
        if not dt > 0.0:
            raise ValueError(f"{self.name}: doStep needs a positive step, got {dt}")
        binding = self._binding or self._require_binding()
        binding.plan.builtin_do_step(binding.index, t, dt)

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        """Read the FMU's outputs into the engine (ports read the engine)."""
        self._require_binding().plan.read_outputs(self)

    def snapshot_state(self) -> Any:
        """The FMU's state now (fmi2GetFMUstate / fmi3GetFMUState)."""
        return self.instance.getFMUstate()

    def restore_state(self, snapshot: Any, t: float) -> None:
        """Return the FMU to `snapshot`, a state it had at time `t`."""
        self.instance.setFMUstate(snapshot)
        self.t = t
        self._update_output_states(t)

    def can_rollback(self) -> bool:
        """Whether the FMU can save and restore its state, or a subclass overrides
        snapshot_state and restore_state."""
        return self.can_get_set_state or super().can_rollback()

    def why_no_rollback(self) -> str:
        standard = self.info.standard
        if standard.has_fmu_state:
            return ""
        return (f"{self.info.path.name} is an {standard.name} FMU, and {standard.name} has no "
                "FMU state to save and restore")

    def get_state(self) -> dict[str, dict[str, Any]]:
        """Outputs, parameters and the other non-fixed, non-local variables, read from the FMU
        (one fmi2Get call per value type)."""
        getters: dict[Any, Any] = {PortType.REAL: self.instance.getReal,
                                   PortType.INT: self.instance.getInteger,
                                   PortType.BOOL: self.instance.getBoolean}
        texts = {"String": self.instance.getString, "Binary": self.instance.getBinary}
        getters.update({kind: texts[kind] for kind in self.info.standard.text_types})
        by_type: dict[str, list[Any]] = {}
        for variable in self.info.all_variables:
            kind = PORT_TYPES.get(variable.type, variable.type)
            if (variable.variability != "fixed" and variable.causality != "local"
                    and kind in getters and not getattr(variable, "dimensions", None)):
                by_type.setdefault(kind, []).append(variable)
        state: dict[str, dict[str, Any]] = {}
        for kind, variables in by_type.items():
            if kind == "Binary":  # one call each: the engine's refusal then names the variable
                values = [self._binary_value(v) for v in variables]
            else:
                values = getters[kind]([v.valueReference for v in variables])
            for variable, value in zip(variables, values, strict=True):
                state[variable.name] = {"value": value, "unit": variable_unit(variable)}
        for name, value in self.parameters.items():
            state.setdefault(name, {"value": value, "unit": self.info.parameters[name].unit})
        return state

    def _binary_value(self, variable: Any) -> bytes:
        try:
            return self.instance.getBinary([variable.valueReference])[0]
        except FMUError as error:
            raise FMUError(f"{error} (variable {variable.name!r})", component=error.component,
                           status=error.status, fmu_message=error.fmu_message) from error

    def _require_binding(self) -> Any:
        if self._binding is None:
            raise ConfigurationError(f"{self.name}: initialize the component (or its System) "
                                     "first")
        return self._binding

    def reset(self) -> None:
        """Free the FMU instance and forget the run: a later initialize starts afresh."""
        if self.instance.alive():
            self.instance.freeInstance()
        super().reset()

    def free(self) -> None:
        """Free the instance and unload the binary; afterwards every use of the FMU raises
        FMUError."""
        self.reset()
        self._finalizer()


# What a class of the user's may override that changes how an event is handled: the engine then
# leaves the handling to Python
_EVENT_HOOKS = ("_handle_events_internal", "_update_output_states", "reinitialize",
                "_apply_parameters_starts", "_apply_input_starts", "_set_event_input")

# Integer ports cross the FMI boundary as C ints (FMI 3.0 UInt32 and 64-bit integers are Real
# ports, exact up to 2**53)
INT_MIN, INT_MAX = -(2**31), 2**31 - 1


def _typed_input(kind: PortType, value: float) -> float | int | bool:
    if kind == PortType.INT:
        return round(value)
    if kind == PortType.BOOL:
        return value != 0.0
    return value


def _checked_tolerance(tolerance: float | None, where: str) -> float | None:
    if tolerance is None:
        return None
    if isinstance(tolerance, bool) or not isinstance(tolerance, int | float) \
            or not (math.isfinite(tolerance) and tolerance > 0):
        raise ConfigurationError(f"{where} must be a positive number, got {tolerance!r}")
    return float(tolerance)


def _first_given(*values: float | None) -> float | None:
    return next((v for v in values if v is not None), None)


def _coerce_parameter(component: str, parameter: Parameter, value: Any) -> Any:
    if type(value) is float and parameter.type == PortType.REAL:  # the common case
        return value
    where = f"{component}.{parameter.name}"
    if parameter.fmi_type == "Binary":
        if not isinstance(value, bytes | bytearray):
            raise ConfigurationError(f"{where} is Binary; got {type(value).__name__} {value!r}")
        return bytes(value)
    if parameter.type == PortType.REAL:
        if is_quantity(value):
            try:
                return magnitude_in(value, parameter.unit)
            except units.DimensionalityError as exc:
                raise ConfigurationError(f"{where}: {value} is not convertible to "
                                         f"{parameter.unit or 'a plain number'}") from exc
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise ConfigurationError(f"{where} is Real; got {type(value).__name__} {value!r}")
        return float(value)
    try:
        spec = PortSpec(parameter.name, parameter.type, "in")
        return spec.coerce(value)
    except TypeError as exc:
        raise ConfigurationError(f"{where}: {exc}") from exc


def _chosen_interface(info: FMUInfo, name: str, interface: str) -> FMUInterface:
    """The interface `interface` names ("auto": the first of INTERFACES the FMU has)."""
    if interface == "auto":
        return next(info.interfaces[n] for n in INTERFACES if n in info.interfaces)
    if interface not in INTERFACES:
        raise ConfigurationError(f"component {name!r}: interface={interface!r} is not one of "
                                 f"'auto', {', '.join(map(repr, INTERFACES))}")
    if interface not in info.interfaces:
        raise ConfigurationError(f"component {name!r}: {info.path.name} has no {interface} "
                                 f"interface (it has {', '.join(info.interfaces)})")
    return info.interfaces[interface]


def _release(free_fmu: Any, instance: FMUInstance, unzip_dir: Path,
             key: tuple[str, int, int] | None) -> None:
    """The finalizer: `free_fmu` is ssx_fmu_free, looked up when the component was made."""
    instance.release(free_fmu)
    extractions.release(unzip_dir, key)
