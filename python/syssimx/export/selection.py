"""Which values of a system an exported FMU shows, and where each lives in the engine.

An exported variable is a member's Real, Integer or Boolean port or parameter named
"Component.port", or one of the system's own outputs: the events handled inside so far and the
last one's time. A String or Binary one is refused: the engine holds every port as a double."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from ..components.fmu import FMUComponent
from ..core.port import PortType
from ..errors import ConfigurationError

EXPORTED_TYPES = {PortType.REAL: "real", PortType.INT: "integer", PortType.BOOL: "boolean"}
EVENT_COUNT = "events"
LAST_EVENT_TIME = "last_event_time"


@dataclass(frozen=True)
class ExportedVariable:
    """One variable of the exported FMU. `role` is "input", "output" or "parameter" of a
    member, or "events"/"last_event_time" of the system; `component` is the member's index in
    the engine (-1 for the system's own), `index` the engine's port index of an input or output
    and the member FMU's value reference of a parameter; `value_type` "real", "integer" or
    "boolean"."""

    name: str
    value_reference: int
    role: str
    component: int
    index: int
    unit: str | None = None
    start: float | None = None
    description: str | None = None
    value_type: str = "real"


def select(system: Any, inputs: Sequence[str] | None, outputs: Sequence[str] | None,
           parameters: Sequence[str]) -> list[ExportedVariable]:
    """The exported variables, value references 1, 2, ... in the order inputs, outputs,
    parameters, then the system's event count and last event time. inputs None: every Real
    member input no connection drives; outputs None: every member output (String and Binary
    ones left out)."""
    driven = {(c.dst_comp, c.dst_port) for c in system.connections}
    if inputs is None:
        inputs = [f"{c.name}.{p}" for c in system.components.values()
                  for p in c.engine_inputs()
                  if c.input_specs[p].type in EXPORTED_TYPES and (c.name, p) not in driven]
    if outputs is None:
        outputs = [f"{c.name}.{p}" for c in system.components.values()
                   for p in c.engine_outputs() if c.output_specs[p].type in EXPORTED_TYPES]
    chosen = [*(("input", n) for n in inputs), *(("output", n) for n in outputs),
              *(("parameter", n) for n in parameters)]
    names = [name for _, name in chosen]
    repeated = sorted({n for n in names if names.count(n) > 1})
    if repeated:
        raise ConfigurationError(f"{system.name}: exported more than once: {repeated}")
    index = {name: i for i, name in enumerate(system.components)}
    exported = [_member_variable(system, index, role, name, vr, driven)
                for vr, (role, name) in enumerate(chosen, start=1)]
    own = len(exported) + 1
    exported.append(ExportedVariable(EVENT_COUNT, own, "events", -1, -1,
                                     description="events inside so far: those "
                                     "the indicators made and the members' own",
                                     value_type="integer"))
    exported.append(ExportedVariable(LAST_EVENT_TIME, own + 1, "last_event_time", -1, -1,
                                     unit="s", description="time of the last event handled "
                                     "inside (the start time before the first)"))
    return exported


def _member_variable(system: Any, index: dict[str, int], role: str, name: str, vr: int,
                     driven: set[tuple[str, str]]) -> ExportedVariable:
    component_name, dot, port = name.partition(".")
    if not dot or component_name not in system.components:
        raise ConfigurationError(f"{system.name}: exported {role} {name!r} is not "
                                 f"'Component.{role}' of a component of "
                                 f"{sorted(system.components)}")
    component = system.components[component_name]
    where = f"{system.name}: exported {role} {name!r}"
    if role == "parameter":
        return _parameter(component, index[component_name], name, vr, where)
    specs = component.input_specs if role == "input" else component.output_specs
    ports = component.engine_inputs() if role == "input" else component.engine_outputs()
    if port not in ports:
        raise ConfigurationError(f"{where}: {component_name!r} has no {role} {port!r}; "
                                 f"{role}s: {sorted(ports)}")
    spec = specs[port]
    value_type = _exported_type(spec.type, where)
    if role == "input" and (component_name, port) in driven:
        raise ConfigurationError(f"{where}: a connection inside the system drives it")
    start = _input_start(component, port) if role == "input" else None
    return ExportedVariable(name, vr, role, index[component_name], ports.index(port),
                            spec.unit, start, spec.description, value_type)


def _exported_type(port_type: PortType, where: str) -> str:
    if port_type not in EXPORTED_TYPES:
        raise ConfigurationError(f"{where}: it is a {port_type.name} and only Real, Integer "
                                 "and Boolean values are exported (the engine holds values "
                                 "as numbers)")
    return EXPORTED_TYPES[port_type]


def _parameter(component: Any, component_index: int, name: str, vr: int,
               where: str) -> ExportedVariable:
    if not isinstance(component, FMUComponent):
        raise ConfigurationError(f"{where}: only FMU components have parameters")
    port = name.partition(".")[2]
    parameter = component.info.parameters.get(port)
    if parameter is None:
        raise ConfigurationError(f"{where}: {component.name!r} has no parameter {port!r}")
    value_type = _exported_type(parameter.type, where)
    return ExportedVariable(name, vr, "parameter", component_index, parameter.value_reference,
                            parameter.unit, float(component.parameters[port]),
                            value_type=value_type)


def _input_start(component: Any, port: str) -> float:
    """What the input holds before the importer sets it: the value the user set, else the
    member's own start (an FMU's declared start, 0 when it declares none)."""
    start = float(component.input_start(port))
    if math.isnan(start) and isinstance(component, FMUComponent):
        return float(component.info.input_starts[port])
    return 0.0 if math.isnan(start) else start
