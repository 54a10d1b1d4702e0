"""CoSimComponent: the base class of every component, and of pure Python components.

A component lives in an engine system (the one of the System it was added to, or a private
one-component system when it is used on its own). The engine steps it; a pure Python component
is stepped through callbacks into the hooks below (engine inputs -> `inputs` ports ->
`_do_step_internal` -> `_update_output_states` -> `outputs` ports -> engine outputs).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, MutableMapping
from copy import deepcopy
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..bridge.plan import bind
from ..bridge.standalone import StandaloneSystem, standalone_system
from ..core.element_map import made_items
from ..core.events import EventIndicator
from ..core.port import Port, PortSpec, PortType
from ..core.suggest import did_you_mean
from ..errors import ConfigurationError

if TYPE_CHECKING:
    from ..bridge.plan import Binding, EnginePlan
    from .history import ComponentHistory

EventHandler = Callable[[Any, list[str], float], None]

# the port types the engine carries (a STRING or BINARY port's value: the number of its text
# or bytes in the system)
ENGINE_TYPES = (PortType.REAL, PortType.INT, PortType.BOOL, PortType.STRING, PortType.BINARY)


@dataclass(frozen=True)
class ComponentCheckpoint:
    """A component's state at `time`: its solver state (snapshot_state), port values,
    parameters and subclass metadata. Restorable on the component that took it only."""

    owner: CoSimComponent
    time: float
    solver_state: Any
    inputs: dict[str, Any]
    outputs: dict[str, Any]
    parameters: dict[str, Any]
    metadata: Any = None


class CoSimComponent:
    """Base class of co-simulation components.

    A pure Python component overrides `_do_step_internal(t, dt)` and
    `_update_output_states(t, event_names)` (and optionally `_initialize_component(t0)`,
    `evaluate_outputs`, `snapshot_state`/`restore_state` for rollback and
    `_handle_events_internal`). Declared `direct_feedthrough = {"y": {"u"}}` is respected.
    """

    def __init__(self, name: str, label: str | None = None, group: str | None = None) -> None:
        self.name = name
        self.label = label if label is not None else name
        self.group = group
        # mappings: dicts, or (an FMU's) ElementMaps that make array elements when asked for
        self.input_specs: MutableMapping[str, PortSpec] = {}
        self.output_specs: MutableMapping[str, PortSpec] = {}
        self.inputs: MutableMapping[str, Port] = {}
        self.outputs: MutableMapping[str, Port] = {}
        self.parameters: MutableMapping[str, Any] = {}
        self.direct_feedthrough: MutableMapping[str, set[str]] = {}
        self.event_indicators: dict[str, EventIndicator] = {}
        self.event_handlers: dict[str, list[EventHandler]] = {}
        # event name -> the EVENT inputs it arrives on (set by the System from its connections)
        self._event_routes: dict[str, set[str]] = {}
        self._binding: Binding | None = None
        self.t = 0.0
        self._private_system: StandaloneSystem | None = None
        self._parameter_defaults: dict[str, Any] | None = None  # see get_default_parameters

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.name!r})"

    @property
    def t(self) -> float:
        """The component's time, the one it set last or where its System's last run ended when
        that came later (a run does not touch every component)."""
        binding = self._binding
        if binding is not None and binding.plan.runs > self._t_runs:
            return binding.plan.time
        return self._t

    @t.setter
    def t(self, value: float) -> None:
        self._t = value
        binding = self._binding
        self._t_runs = binding.plan.runs if binding is not None else 0

    # ---------------------------------------------------------------- ports
    def _make_port(self, spec: PortSpec) -> Port:
        return Port(spec)

    def _sync_ports(self) -> None:
        """Create a Port for every spec added since (subclasses fill the specs in __init__;
        the ports of an FMU's array elements are made when asked for)."""
        if self._parameter_defaults is None:
            self._remember_default_parameters()
        for specs, ports in ((self.input_specs, self.inputs), (self.output_specs, self.outputs)):
            made = made_items(ports)  # a dict lookup per port; an ElementMap's for the rest
            for name, spec in made_items(specs).items():
                port = made.get(name) or ports.get(name)
                # identity first: comparing every field of every spec made add_connection slow
                if port is None or (port.spec is not spec and port.spec != spec):
                    ports[name] = self._make_port(spec)

    def engine_outputs(self) -> list[str]:
        """Names of the outputs the engine carries, in engine order."""
        return [n for n, s in self.output_specs.items() if s.type in ENGINE_TYPES]

    def engine_inputs(self) -> list[str]:
        """The names of the inputs the engine moves values into (every non-event input)."""
        return [n for n, s in self.input_specs.items() if s.type in ENGINE_TYPES]

    def why_no_port(self, name: str) -> str:
        """Why `name` is no port although the component knows it ("" when it does not)."""
        return ""

    def input_start(self, name: str) -> float:
        """The value an input holds until a connection drives it."""
        return float(self.inputs[name].raw())

    def feedthrough(self) -> dict[str, set[str]]:
        """Output -> inputs it depends on directly (the declared `direct_feedthrough`)."""
        return {name: set(self.direct_feedthrough.get(name, ())) for name in self.engine_outputs()}

    def undeclared_outputs(self) -> set[str]:
        """The outputs whose dependencies the component does not declare (their feedthrough
        is the standard's assumption, every input); a Python component declares all."""
        return set()

    # ---------------------------------------------------------------- parameters
    def _remember_default_parameters(self) -> None:
        """The parameters before anything changed them: at the end of construction (the
        first port sync) or at the first set_parameters, whichever comes first."""
        if self._parameter_defaults is None:
            self._parameter_defaults = deepcopy(self.parameters)

    def get_default_parameters(self) -> dict[str, Any]:
        """The parameters as the component declared them (an FMU: its modelDescription start
        values), whatever set_parameters changed since."""
        self._remember_default_parameters()
        return deepcopy(self._parameter_defaults or {})

    def set_parameters(self, **parameters: Any) -> None:
        """Set parameters by name; they apply from the next initialize (or reinitialize)."""
        self._remember_default_parameters()
        for name, value in parameters.items():
            if name not in self.parameters:
                raise ConfigurationError(
                    f"component {self.name!r} has no parameter {name!r}"
                    f"{did_you_mean(name, self.parameters)}; "
                    f"known parameters: {sorted(self.parameters) or 'none'}")
            self.parameters[name] = value

    def get_parameters(self, *names: str) -> dict[str, Any]:
        """The parameters named (all of them when none is named), by name."""
        unknown = [n for n in names if n not in self.parameters]
        if unknown:
            raise ConfigurationError(f"component {self.name!r} has no parameter {unknown[0]!r}"
                                     f"{did_you_mean(unknown[0], self.parameters)}; "
                                     f"known parameters: {sorted(self.parameters) or 'none'}")
        return {n: self.parameters[n] for n in (names or self.parameters)}

    # ---------------------------------------------------------------- inputs / outputs
    def set_inputs(self, signals: Mapping[str, Any], t: float | None = None) -> None:
        """Set inputs by name: numbers, or pint quantities converted to the input's unit."""
        self._sync_ports()
        for name, value in signals.items():
            if name not in self.inputs:
                why = self.why_no_port(name) or did_you_mean(name, self.inputs)
                raise ConfigurationError(f"component {self.name!r} has no input {name!r}{why}; "
                                         f"inputs: {sorted(self.inputs) or 'none'}")
            self.inputs[name].set(value, t)
        if self._binding is not None:
            self._binding.plan.write_inputs(self)

    def get_outputs(self) -> dict[str, Any]:
        """The current outputs by name, as pint quantities where the port has a unit."""
        self._sync_ports()
        return {name: port.get() for name, port in self.outputs.items()}

    def evaluate_outputs(self, inputs: Mapping[str, Any], t: float | None = None
                         ) -> dict[str, Any]:
        """Zero-time evaluation used by algebraic loops: outputs for these inputs, no step."""
        for name, value in inputs.items():
            self.inputs[name].set(value, t)
        return {name: port.get() for name, port in self.outputs.items()}

    # ---------------------------------------------------------------- events
    def add_event_indicator(self, name: str, func: Callable[[Any], float] | None = None,
                            direction: int = 0, variable: str | None = None) -> None:
        """Declare a zero crossing; creates the EVENT output port `name`.

        Args:
            name: the event, and its EVENT output port.
            func: ``func(component) -> float``, evaluated in Python (give it or `variable`).
            direction: -1 falling, +1 rising, 0 both.
            variable: an output whose value is the indicator, evaluated in C.
        """
        if (func is None) == (variable is None):
            raise ConfigurationError(f"{self.name}.{name}: give exactly one of func= or variable=")
        if direction not in (-1, 0, 1):
            raise ConfigurationError(f"{self.name}.{name}: direction must be -1, 0 or +1")
        if name in self.event_indicators or (name in self.output_specs
                                            and self.output_specs[name].type != PortType.EVENT):
            raise ConfigurationError(f"{self.name}: the name {name!r} is already in use")
        if variable is not None and variable not in self.engine_outputs():
            raise ConfigurationError(f"{self.name}.{name}: variable {variable!r} is not an "
                                     f"output{self.why_no_port(variable)}; outputs: "
                                     f"{self.engine_outputs()}")
        self.event_indicators[name] = EventIndicator(name, direction, func, variable)
        self.output_specs[name] = PortSpec(name, PortType.EVENT, "out")

    def add_event_handler(self, event_input: str, handler: EventHandler) -> None:
        """Run `handler(component, event_names, t)` when an event arrives on the EVENT input
        `event_input` (through an EventConnection). Creates that input if missing."""
        spec = self.input_specs.get(event_input)
        if spec is not None and spec.type != PortType.EVENT:
            raise ConfigurationError(f"{self.name}.{event_input} is a {spec.type.name} input, "
                                     "not an EVENT input")
        self.input_specs.setdefault(event_input, PortSpec(event_input, PortType.EVENT, "in"))
        self.event_handlers.setdefault(event_input, []).append(handler)

    def has_event_handling(self) -> bool:
        """Whether events delivered to this component do anything."""
        return (bool(self.event_handlers) or bool(self.self_handled_events())
                or _overrides(self, "_handle_events_internal"))

    def _handle_events_internal(self, event_names: list[str], t: float) -> None:
        """Run the handlers registered with add_event_handler for the EVENT inputs the events
        arrived on, each once; subclasses may override."""
        inputs = dict.fromkeys(port for name in event_names
                               for port in sorted(self._event_routes.get(name, ())))
        for port in inputs:
            self._set_event_input(port, True, t)
            for handler in self.event_handlers.get(port, ()):
                handler(self, list(event_names), t)
            self._set_event_input(port, False, t)

    def _set_event_input(self, port: str, value: bool, t: float) -> None:
        if port in self.inputs:
            self.inputs[port].set(value, t)

    def _set_event_ports(self, t: float | None, event_names: Iterable[str] | None) -> None:
        """EVENT outputs: True for the events that just fired, all False otherwise."""
        names = set(event_names or ())
        # EVENT ports are never array elements: the made ports are all of them
        for port in made_items(self.outputs).values():
            if port.spec.type == PortType.EVENT:
                port.set(port.spec.name in names, t)

    # ---------------------------------------------------------------- lifecycle hooks
    def _initialize_component(self, t0: float) -> None:
        """Set up the component's own state at t0 (a pure Python component may override)."""

    def _do_step_internal(self, t: float, dt: float) -> None:
        raise NotImplementedError(f"{type(self).__name__} must implement _do_step_internal")

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        raise NotImplementedError(f"{type(self).__name__} must implement _update_output_states")

    def _record_outputs(self, t: float) -> None:
        """Called when the engine records a sample at t. The engine stores the outputs itself;
        a subclass may override this to keep extra data of its own."""

    def snapshot_state(self) -> Any:
        """Override with restore_state to give the component rollback: return anything that
        captures its state now."""
        raise NotImplementedError(f"{self.name}: snapshot_state is not implemented")

    def restore_state(self, snapshot: Any, t: float) -> None:
        """Override with snapshot_state: return to `snapshot`, taken at time `t`."""
        raise NotImplementedError(f"{self.name}: restore_state is not implemented")

    def can_rollback(self) -> bool:
        """Whether the hybrid algorithm can restore this component (needed by event
        indicators)."""
        return _overrides(self, "snapshot_state") and _overrides(self, "restore_state")

    def why_no_rollback(self) -> str:
        """Why the component can never roll back, whatever a subclass overrides ("" when it
        could)."""
        return ""

    def get_state(self) -> dict[str, dict[str, Any]]:
        """Outputs and parameters as {name: {"value", "unit"}}."""
        state = {name: {"value": port.raw(), "unit": port.spec.unit}
                 for name, port in self.outputs.items() if port.spec.type != PortType.EVENT}
        for name, value in self.parameters.items():
            state.setdefault(name, {"value": value, "unit": None})
        return state

    def set_state(self, state: Mapping[str, Any], t: float) -> None:
        """Restart at t from a physical state {name: {"value", "unit"} or value}: the entries
        naming parameters become this instance's start values (reinitialize), those naming
        inputs are set; other entries (outputs) are ignored."""
        def value(entry: Any) -> Any:
            return entry["value"] if isinstance(entry, Mapping) else entry

        inputs = {n: value(v) for n, v in state.items() if n in self.input_specs
                  and self.input_specs[n].type != PortType.EVENT}
        if inputs:
            self.set_inputs(inputs, t)
        self.reinitialize(t, **{n: value(v) for n, v in state.items() if n in self.parameters})

    def reinitialize(self, t: float, **start_values: Any) -> None:
        """Start again at t, with `start_values` overriding parameters for this start only:
        _initialize_component(t) and the outputs (FMUComponent: a fresh FMU instance)."""
        unknown = sorted(set(start_values) - set(self.parameters))
        if unknown:
            raise ConfigurationError(f"component {self.name!r} has no parameter {unknown[0]!r}"
                                     f"{did_you_mean(unknown[0], self.parameters)}; "
                                     f"known parameters: {sorted(self.parameters) or 'none'}")
        saved = self.parameters
        self.parameters = {**saved, **start_values}
        try:
            self._sync_ports()
            self.t = t
            self._initialize_component(t)
            self._update_output_states(t)
        finally:
            self.parameters = saved
        if self._binding is not None:
            self._binding.plan.push_outputs(self)

    def reinitialize_instance(self, t: float) -> None:
        """SysSimX's name: start again at t with the current parameters (reinitialize)."""
        self.reinitialize(t)

    def soft_reset(self, t0: float = 0.0) -> None:
        """Back to the initial state at t0 with the current parameters. Used on its own, the
        component's history restarts at t0; in a System, initialize the System before its
        next run."""
        if self._binding is None or self._private_system is not None:
            self._standalone().initialize(t0)
        else:
            self.reinitialize(t0)

    # ---------------------------------------------------------------- checkpoints
    def checkpoint(self) -> ComponentCheckpoint:
        """The component's state now, for restore_checkpoint (needs rollback support)."""
        if not self.can_rollback():
            raise ConfigurationError(f"{self.name}: cannot take a checkpoint: the component "
                                     "does not support rollback (snapshot_state/restore_state)")
        self._sync_ports()
        return ComponentCheckpoint(
            self, self.t, self.snapshot_state(),
            {n: p.raw() for n, p in self.inputs.items()},
            {n: p.raw() for n, p in self.outputs.items()},
            deepcopy(self.parameters), deepcopy(self._checkpoint_metadata()))

    def restore_checkpoint(self, checkpoint: ComponentCheckpoint) -> None:
        """Return to a checkpoint of this component: solver state, time, ports, parameters."""
        if checkpoint.owner is not self:
            raise ConfigurationError(f"{self.name}: the checkpoint belongs to "
                                     f"{checkpoint.owner.name!r}")
        self.parameters = deepcopy(checkpoint.parameters)
        self._restore_checkpoint_metadata(deepcopy(checkpoint.metadata))
        self._publish_ports(checkpoint)
        self.restore_state(checkpoint.solver_state, checkpoint.time)
        self.t = checkpoint.time
        self._publish_ports(checkpoint)
        if self._private_system is not None and self._private_system.is_initialized:
            self._private_system.restart_recording(checkpoint.time)
            self._publish_ports(checkpoint)  # the restart gave unconnected inputs their starts

    def _publish_ports(self, checkpoint: ComponentCheckpoint) -> None:
        """The checkpoint's port values, in the ports and the engine. (An FMU's ports read
        the engine, which restore_state refreshed from the FMU: this writes them back.)"""
        for ports, values in ((self.inputs, checkpoint.inputs),
                              (self.outputs, checkpoint.outputs)):
            for name, value in values.items():
                ports[name]._raw = value
        if self._binding is not None:
            self._binding.plan.write_inputs(self)
            self._binding.plan.push_outputs(self)

    def _checkpoint_metadata(self) -> Any:
        """State a subclass keeps outside its solver (e.g. the active model); checkpointed."""
        return None

    def _restore_checkpoint_metadata(self, metadata: Any) -> None:
        """Restore what _checkpoint_metadata returned."""

    @property
    def history(self) -> ComponentHistory:
        """The recorded outputs (SysSimX's ComponentHistory over the engine's samples)."""
        from .history import ComponentHistory

        return ComponentHistory(self)

    def self_handled_events(self) -> list[str]:
        """Event indicators whose events the component handles itself, with no
        EventConnection (a MultiComponent's region boundaries)."""
        return []

    # ---------------------------------------------------------------- the engine plan
    def _add_to_plan(self, plan: EnginePlan) -> None:
        """Add the component to the engine system being built: a Python component, stepped
        through its hooks."""
        plan.add_python_component(self, self._python_hooks(engine_steps=False))

    def _python_hooks(self, engine_steps: bool) -> set[str]:
        """The engine hooks (bridge.plan.HOOKS) this component runs in Python. engine_steps:
        the engine steps the component itself (an FMU), so only what the class overrides."""
        hooks = set()
        if not engine_steps or _overrides(self, "_do_step_internal") \
                or _overrides(self, "_update_output_states"):
            hooks.add("do_step")
        if not engine_steps or _overrides(self, "evaluate_outputs"):
            hooks.add("evaluate_outputs")
        if (_overrides(self, "snapshot_state") or _overrides(self, "restore_state")) \
                and self.can_rollback():
            hooks.update(("snapshot", "restore"))
        if self.has_event_handling():
            hooks.add("handle_events")
        if _overrides(self, "_record_outputs"):
            hooks.add("record")
        return hooks

    # Called by the System (or the private system) once the engine plan exists, with the
    # tolerance given to System.initialize (used by FMU components).
    def _start(self, t0: float, tolerance: float | None = None) -> None:
        self._sync_ports()
        self.t = t0
        self._initialize_component(t0)
        self._update_output_states(t0)
        self._set_event_ports(t0, None)
        if self._binding is not None:
            self._binding.plan.push_outputs(self)

    # ---------------------------------------------------------------- standalone use
    def _standalone(self) -> StandaloneSystem:
        if self._private_system is None:
            self._private_system = standalone_system(self)
        return self._private_system

    def initialize(self, t0: float = 0.0) -> None:
        """Initialize the component on its own, in a private one-component system."""
        self._standalone().initialize(t0)

    def do_step(self, t: float, dt: float) -> None:
        """Advance a component used on its own from t to t + dt (records a sample)."""
        system = self._standalone()
        system.run(t, t + dt, dt)

    def get_history_arrays(self, port_names: list[str] | None = None
                           ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """(time, {output: values}) recorded by the engine system the component runs in, copied
        (the engine's buffers move when it records again; System results are zero-copy)."""
        if self._binding is None:
            return np.empty(0), {n: np.empty(0) for n in self.engine_outputs()}
        t, values = self._binding.plan.component_history(self)
        names = self.engine_outputs() if port_names is None else port_names
        return t.copy(), {n: np.array(values[n]) for n in names}

    def get_history(self, port_names: list[str] | None = None) -> dict[str, dict[str, Any]]:
        """{output: {"time", "values", "unit"}}."""
        t, values = self.get_history_arrays(port_names)
        return {n: {"time": t, "values": v, "unit": self.output_specs[n].unit}
                for n, v in values.items()}

    def reset(self) -> None:
        """Forget the run: a later initialize starts from scratch."""
        self.t = 0.0
        self._private_system = None
        bind(self, None)

    def free(self) -> None:
        """Release what the component holds (nothing for a pure Python component)."""
        self.reset()


# Classes whose hooks the engine runs itself (no Python per call); any other class's hook,
# a user's or a syssimx Python component's like MultiComponent, is called back through Python.
_ENGINE_BUILT_IN = ("syssimx.components.base", "syssimx.components.fmu")


def _overrides(component: object, method: str) -> bool:
    """Whether the component's class replaces the method of the built-in class defining it."""
    own = getattr(type(component), method)
    for klass in type(component).__mro__:
        if klass.__module__ in _ENGINE_BUILT_IN and method in vars(klass):
            return own is not vars(klass)[method]
    return False
