"""A System from a flattened SSP structure: FMU components with their parameters, the
connections with their transformations and unit conversions, each checked against the FMU."""

from __future__ import annotations

import math
from typing import Any

from ..components.fmu import FMUComponent
from ..core.port import PortType
from ..errors import ConfigurationError
from ..fmu.info import variable_unit
from ..ssp_format.errors import SSPError
from ..ssp_format.unsupported import Unsupported
from ..system.connection import Connection
from ..system.system import System
from ..units import (
    DIMENSIONLESS_SPELLINGS,
    conversion,
    is_quantity,
    magnitude_in,
    quantity,
    si_expression,
)
from .parameters import ParameterValue
from .structure import ComponentEntry, ConnectionEntry, Connector, Structure
from .units import UnitDefinition, defined_conversion

# the SSP connector types each FMU variable type may be declared as
_SSP_TYPES = {PortType.REAL: {"Real"}, PortType.INT: {"Integer", "Enumeration"},
              PortType.BOOL: {"Boolean"}, PortType.STRING: {"String"},
              PortType.BINARY: {"Binary"}}


def build(structure: Structure, unsupported: Unsupported) -> System:
    system = System(structure.name)
    for entry in structure.components.values():
        try:
            component = FMUComponent(entry.path, entry.source, interface=entry.interface)
        except ConfigurationError as exc:
            raise SSPError(f"{entry.label}: {exc}") from exc
        for connector in entry.connectors.values():
            _check_connector(component, connector, structure.units)
        _set_values(component, entry, structure.units, unsupported)
        system.add_component(component)
    for c in structure.connections:
        if c.dst[1] in system.components[c.dst[0]].triggered_clocks:
            _connect_clock(system, c)
            continue
        src_spec = system.components[c.src[0]].output_specs.get(c.src[1])
        dst_spec = system.components[c.dst[0]].input_specs.get(c.dst[1])
        factor, offset, convert = c.factor, c.offset, c.convert_units
        try:
            if convert and src_spec is not None and dst_spec is not None:
                units = _connector_unit(structure, c.src), _connector_unit(structure, c.dst)
                defined = defined_conversion(structure.units, *units)
                if defined is not None:  # the SSD's own definitions, not pint's
                    factor, offset, convert = factor * defined[0], \
                        factor * defined[1] + offset, False
            system.add_connection(Connection(c.src[0], c.src[1], c.dst[0], c.dst[1],
                                             factor, offset, convert))
        except (ConfigurationError, ValueError) as exc:
            raise SSPError(f"{c.label}: {exc}") from exc
    return system


def _connect_clock(system: System, c: ConnectionEntry) -> None:
    """A connection to a triggered input clock: a clock connection (from an output clock)."""
    try:
        system.add_clock_connection(".".join(c.src), ".".join(c.dst))
    except ConfigurationError as exc:
        raise SSPError(f"{c.label}: {exc}") from exc


def _connector_unit(structure: Structure, endpoint: tuple[str, str]) -> str | None:
    connector = structure.components[endpoint[0]].connectors.get(endpoint[1])
    return connector.unit if connector is not None else None


def _check_connector(component: FMUComponent, connector: Connector,
                     units: dict[str, UnitDefinition]) -> None:
    """The connector names a variable of the FMU of the same kind, type and unit (a unit the
    SSD defines is compared by its definition, not its name). A clock (an output clock, a
    triggered input clock: SSP 1.0 has no type for it) is a connector without a type."""
    clocks = {"input": component.triggered_clocks, "output": component.output_clocks}.get(
        connector.kind, [])
    if connector.name in clocks and connector.type in (None, "Clock"):
        return
    specs = {"input": component.input_specs, "output": component.output_specs}.get(
        connector.kind, {})
    parameter = component.info.parameters.get(connector.name)
    spec = specs.get(connector.name)
    kind = spec.type if spec is not None else parameter.type if parameter is not None else None
    if kind is None:
        why = component.why_no_port(connector.name)
        raise SSPError(f"{connector.label}: {component.name!r} ({component.fmu_path}) has no "
                       f"{connector.kind} {connector.name!r}{why}")
    if connector.type is not None and connector.type not in _SSP_TYPES.get(kind, set()):
        raise SSPError(f"{connector.label}: type {connector.type} does not match the FMU's "
                       f"{kind.name} variable {connector.name!r} of {component.name!r}")
    unit = spec.unit if spec is not None else parameter.unit  # type: ignore[union-attr]
    variable = component.info.variables.get(connector.name)
    declared = variable_unit(variable) if variable is not None else None  # as the FMU spells it
    defined = units.get(connector.unit) if connector.unit else None
    if connector.unit and unit and connector.unit != declared and _differ(
            defined.pint_unit() if defined is not None else connector.unit, unit):
        raise SSPError(f"{connector.label}: unit {connector.unit!r} does not match the FMU's "
                       f"unit {unit!r} of {component.name}.{connector.name}")


def _differ(a: str, b: str) -> bool:
    """Whether a value in unit `a` is not the same number in unit `b`."""
    if a.strip() in DIMENSIONLESS_SPELLINGS and b.strip() in DIMENSIONLESS_SPELLINGS:
        return False
    try:
        scale, offset = conversion(a, b)
    except Exception:  # an unreadable unit (ValueError) or another quantity (pint's error)
        return a != b
    return not (math.isclose(scale, 1.0, rel_tol=1e-12) and abs(offset) <= 1e-12)


def _set_values(component: FMUComponent, entry: ComponentEntry,
                units: dict[str, UnitDefinition], unsupported: Unsupported) -> None:
    """Each bound value, in order (a later one wins): a parameter's value or an input's
    start; a value for neither is left out (one warning, an error under strict)."""
    for value in entry.parameters:
        is_input = value.name in component.input_specs
        if not is_input and value.name not in component.info.parameters:
            unsupported.ignore(f"{value.where}: component {component.name!r} has no parameter "
                               f"or input {value.name!r}{component.why_no_port(value.name)}",
                               "the value is ignored")
            continue
        target = component.input_specs[value.name].unit if is_input \
            else component.info.parameters[value.name].unit
        try:
            number = _in_units(value, units, target)
            if is_input:
                spec = component.input_specs[value.name]
                component.set_inputs({value.name: magnitude_in(number, spec.unit)
                                      if is_quantity(number) else number})
            else:
                component.set_parameters(**{value.name: number})
        except (ConfigurationError, ValueError, TypeError) as exc:
            raise SSPError(f"{value.where}: {exc}") from exc
        except Exception as exc:  # pint's own errors (a dimension mismatch, an unknown unit)
            if type(exc).__module__.split(".")[0] != "pint":
                raise
            raise SSPError(f"{value.where}: {component.name}.{value.name}: "
                           f"{exc or type(exc).__name__}") from exc


def _in_units(value: ParameterValue, units: dict[str, UnitDefinition],
              target: str | None) -> Any:
    """The value in the FMU variable's unit `target`, or a pint quantity in its own unit
    for the FMU component to convert. A unit the parameter set or the SSD defines (ssc:Units,
    to SI base units) converts by that definition, else by pint from its name."""
    number: Any = value.value
    if not value.unit or not isinstance(number, float) \
            or value.unit.strip() in DIMENSIONLESS_SPELLINGS or value.unit == target:
        return number
    definition = value.definition or units.get(value.unit)
    if definition is None:
        return quantity(number, value.unit)
    si = definition.factor * number + definition.offset
    defined_target = units.get(target) if target else None
    if defined_target is None:
        return quantity(si, si_expression(definition.exponents))
    if defined_target.exponents != definition.exponents:
        raise ValueError(f"unit {value.unit!r} and the FMU's unit {target!r} measure "
                         "different quantities")
    return (si - defined_target.offset) / defined_target.factor
