"""Parameter bindings: values inline (ssd:ParameterValues) or from .ssv files, renamed and
transformed by parameter mappings inline or from .ssm files.

FMPy's reader keeps a value as text and drops the mapping's transformation; this reads each
value as its SSP type with its unit, so a value in another unit converts through pint.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from .archive import Package, resolve
from .documents import NS, element_label, local_name, parse
from .errors import SSPError
from .unsupported import Unsupported

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
            sets = [(parse(path, "ssv", package.shown(path)), package.shown(path))]
        else:
            sets = [(s, where) for s in binding.iterfind("ssd:ParameterValues/ssv:ParameterSet",
                                                         NS)]
        mapping = _mapping(binding, package, unsupported)
        prefix = binding.get("prefix", "")
        for parameter_set, origin in sets:
            for parameter in parameter_set.iterfind("ssv:Parameters/ssv:Parameter", NS):
                value = _value(parameter, origin, unsupported)
                if value is None:
                    continue
                values.append(_mapped(value, mapping, prefix))
    return values


def _value(parameter: Any, origin: str, unsupported: Unsupported) -> ParameterValue | None:
    name = parameter.get("name")
    where = f"{origin}: {element_label(parameter)}"
    for kind in _TYPES:
        typed = parameter.find(f"ssv:{kind}", NS)
        if typed is None:
            continue
        text = typed.get("value")
        try:
            value: float | int | bool | str = {
                "Real": float, "Integer": int, "Enumeration": int, "String": str,
                "Boolean": lambda t: {"true": True, "false": False}[t.strip()],
            }[kind](text)
        except (KeyError, ValueError, TypeError) as exc:
            raise SSPError(f"{where}: {kind} value {text!r} is not a {kind.lower()}") from exc
        return ParameterValue(name, value, typed.get("unit"), where)
    kinds = [local_name(child) for child in parameter]
    unsupported.warn(f"parameter type {kinds[0] if kinds else 'none'!r}", where)
    return None


@dataclass(frozen=True)
class _Entry:
    target: str
    factor: float
    offset: float


def _mapping(binding: Any, package: Package,
             unsupported: Unsupported) -> dict[str, _Entry]:
    mapping: dict[str, _Entry] = {}
    for element in binding.iterfind("ssd:ParameterMapping", NS):
        source = element.get("source")
        shown = package.shown(package.ssd)
        if source is not None:
            path = resolve(package, source, element_label(element))
            shown = package.shown(path)
            root = parse(path, "ssm", shown)
        else:
            root = element.find("ssm:ParameterMapping", NS)
            if root is None:
                continue
        for entry in root.iterfind("ssm:MappingEntry", NS):
            linear = entry.find("ssc:LinearTransformation", NS)
            for name in _MAP_TRANSFORMATIONS:
                if entry.find(f"ssc:{name}", NS) is not None:
                    unsupported.warn(f"ssc:{name}", f"{shown}: {element_label(entry)}")
            mapping[entry.get("source")] = _Entry(
                entry.get("target"),
                float(linear.get("factor", 1.0)) if linear is not None else 1.0,
                float(linear.get("offset", 0.0)) if linear is not None else 0.0)
    return mapping


def _mapped(value: ParameterValue, mapping: dict[str, _Entry], prefix: str) -> ParameterValue:
    entry = mapping.get(value.name)
    name, number = value.name, value.value
    if entry is not None:
        name = entry.target
        if isinstance(number, float):
            number = entry.factor * number + entry.offset
    if prefix and name.startswith(prefix):
        name = name[len(prefix):]
    return ParameterValue(name, number, value.unit, value.where)
