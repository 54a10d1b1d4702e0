"""Parameter bindings: values inline (ssd:ParameterValues) or from .ssv files, renamed and
transformed by parameter mappings inline or from .ssm files.

FMPy's reader keeps a value as text and drops the mapping's transformation; this reads each
value as its SSP type with its unit, so a value in another unit converts through pint.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..ssp_format.archive import Package, resolve
from ..ssp_format.documents import NS, element_label, local_name, parse
from ..ssp_format.errors import SSPError
from ..ssp_format.unsupported import Unsupported
from .units import UnitDefinition, read_units

_TYPES = ("Real", "Integer", "Boolean", "String", "Enumeration")
_MAP_TRANSFORMATIONS = ("BooleanMappingTransformation", "IntegerMappingTransformation",
                        "EnumerationMappingTransformation")


@dataclass(frozen=True)
class ParameterValue:
    """A value for the parameter `name` (relative to the binding's element), in `unit`."""

    name: str
    value: float | int | bool | str
    unit: str | None
    where: str  # the file and element it came from
    definition: UnitDefinition | None = None  # `unit` as the parameter set defines it


def read_bindings(element: Any, package: Package,
                  unsupported: Unsupported) -> list[ParameterValue]:
    """The values of every ParameterBinding of `element`, in document order."""
    values: list[ParameterValue] = []
    for binding in element.iterfind("ssd:ParameterBindings/ssd:ParameterBinding", NS):
        where = f"{package.shown(package.ssd)}: {element_label(binding)}"
        if binding.get("type", "application/x-ssp-parameter-set") \
                != "application/x-ssp-parameter-set":
            unsupported.warn(f"parameter binding type {binding.get('type')!r}", where)
            continue
        source = binding.get("source")
        if source is not None:
            path = resolve(package, source, element_label(binding))
            sets = [(parse(path, "ssv", package.shown(path), unsupported),
                     package.shown(path))]
        else:
            sets = [(s, where) for s in binding.iterfind("ssd:ParameterValues/ssv:ParameterSet",
                                                         NS)]
        mapping = _mapping(binding, package, unsupported)
        prefix = binding.get("prefix", "")
        for parameter_set, origin in sets:
            units = read_units(parameter_set, "ssv")
            for parameter in parameter_set.iterfind("ssv:Parameters/ssv:Parameter", NS):
                value = _value(parameter, origin, units, unsupported)
                if value is None:
                    continue
                values.extend(_mapped(value, mapping, prefix))
    return values


# XML Schema booleans: true, false, 1, 0 (OMSimulator and libcosim write both forms)
BOOLEANS = {"true": True, "false": False, "1": True, "0": False}


def _value(parameter: Any, origin: str, units: dict[str, UnitDefinition],
           unsupported: Unsupported) -> ParameterValue | None:
    where = f"{origin}: {element_label(parameter)}"
    name = _required(parameter, "name", where)
    for kind in _TYPES:
        typed = parameter.find(f"ssv:{kind}", NS)
        if typed is None:
            continue
        text = typed.get("value")
        try:
            value: float | int | bool | str = {
                "Real": float, "Integer": int, "Enumeration": int, "String": str,
                "Boolean": lambda t: BOOLEANS[t.strip()],
            }[kind](text)
        except (KeyError, ValueError, TypeError) as exc:
            raise SSPError(f"{where}: {kind} value {text!r} is not a {kind.lower()}") from exc
        unit = typed.get("unit")
        return ParameterValue(name, value, unit, where, units.get(unit) if unit else None)
    kinds = [local_name(child) for child in parameter]
    unsupported.warn(f"parameter type {kinds[0] if kinds else 'none'!r}", where)
    return None


@dataclass(frozen=True)
class _Entry:
    target: str
    factor: float
    offset: float


def _mapping(binding: Any, package: Package,
             unsupported: Unsupported) -> dict[str, list[_Entry]]:
    """Each source name with every entry that maps it (a source may have several targets)."""
    mapping: dict[str, list[_Entry]] = {}
    for element in binding.iterfind("ssd:ParameterMapping", NS):
        source = element.get("source")
        shown = package.shown(package.ssd)
        if source is not None:
            path = resolve(package, source, element_label(element))
            shown = package.shown(path)
            root = parse(path, "ssm", shown, unsupported)
        else:
            root = element.find("ssm:ParameterMapping", NS)
            if root is None:
                continue
        for entry in root.iterfind("ssm:MappingEntry", NS):
            linear = entry.find("ssc:LinearTransformation", NS)
            for name in _MAP_TRANSFORMATIONS:
                if entry.find(f"ssc:{name}", NS) is not None:
                    unsupported.warn(f"ssc:{name}", f"{shown}: {element_label(entry)}")
            where = f"{shown}: {element_label(entry)}"
            mapping.setdefault(_required(entry, "source", where), []).append(_Entry(
                _required(entry, "target", where),
                _number(linear, "factor", 1.0, where), _number(linear, "offset", 0.0, where)))
    return mapping


def _required(element: Any, attribute: str, where: str) -> str:
    value = element.get(attribute)
    if value is None:
        raise SSPError(f"{where}: the attribute {attribute!r} is missing")
    return str(value)


def _number(transformation: Any, attribute: str, default: float, where: str) -> float:
    """A LinearTransformation's factor or offset (`default` without the element or the
    attribute)."""
    text = transformation.get(attribute) if transformation is not None else None
    if text is None:
        return default
    try:
        return float(text)
    except ValueError as exc:
        raise SSPError(f"{where}: LinearTransformation {attribute} {text!r} is not a number") \
            from exc


def _mapped(value: ParameterValue, mapping: dict[str, list[_Entry]],
            prefix: str) -> list[ParameterValue]:
    """`value` under each name the mapping gives it (its own when it maps nothing)."""
    entries = mapping.get(value.name)
    if entries is None:
        return [_unprefixed(value, value.name, value.value, prefix)]
    return [_unprefixed(value, entry.target,
                        entry.factor * value.value + entry.offset
                        if isinstance(value.value, float) else value.value, prefix)
            for entry in entries]


def _unprefixed(value: ParameterValue, name: str, number: float | int | bool | str,
                prefix: str) -> ParameterValue:
    if prefix and name.startswith(prefix):
        name = name[len(prefix):]
    return ParameterValue(name, number, value.unit, value.where, value.definition)
