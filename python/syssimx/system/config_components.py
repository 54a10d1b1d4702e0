"""One component of a system description: its class, constructor arguments, parameters and
(syssimx's extensions) a bundled or relative FMU, start values of inputs (held while nothing
drives them), event indicators on outputs and event handlers that restart the component from
its outputs."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..components.base import CoSimComponent
from ..errors import ConfigurationError
from .component_classes import resolve_component_class
from .config_handlers import reinitialize_handler
from .config_source import Source, kind, quoted

COMPONENT_KEYS = ("name", "class", "fmu", "interface", "args", "parameters", "inputs",
                  "dependencies", "event_indicators", "event_handlers")
INDICATOR_KEYS = ("name", "variable", "direction")
HANDLER_KEYS = ("input", "reinitialize")
FMU_CLASS = "syssimx:FMUComponent"


def build_component(source: Source, index: int, entry: Any) -> CoSimComponent:
    """The component of `components[index]`, with its parameters, indicators and handlers."""
    label = f"components[{index}]"
    if not isinstance(entry, dict):
        raise source.error(label, f"must be a mapping with 'name' and 'class' (or 'fmu'), got "
                           f"{kind(entry)} {quoted(entry)}", entry)
    name = entry.get("name")
    if not isinstance(name, str) or not name:
        raise source.error(label, "needs a 'name' (a non-empty string)", entry)
    label = f"{label} {quoted(name)}"
    unknown = sorted(set(entry) - set(COMPONENT_KEYS))
    if unknown:
        raise source.error(label, f"unknown key(s) {unknown}; known: {list(COMPONENT_KEYS)}",
                           entry)
    args = _mapping(source, label, entry, "args")
    if "fmu" in entry:
        if "class" in entry:
            raise source.error(label, "give either 'class' or 'fmu', not both", entry)
        if "fmu_path" in args:
            raise source.error(label, "'fmu' and args.fmu_path both name the FMU", entry)
        spec = FMU_CLASS
        args = {"fmu_path": entry["fmu"], **args}
        if "interface" in entry:
            if "interface" in args:
                raise source.error(label, "'interface' and args.interface both choose the "
                                   "interface", entry)
            args["interface"] = entry["interface"]
    elif "interface" in entry:
        raise source.error(label, "'interface' chooses an FMU's interface: it needs 'fmu' "
                           "(or args.interface of an FMU class)", entry)
    elif "class" in entry:
        spec = entry["class"]
    else:
        raise source.error(label, "needs 'class' (\"module:Class\") or 'fmu' (a bundled FMU "
                           "name or a path to an .fmu file)", entry)
    cls = resolve_component_class(source, label, entry, spec)  # checked before it is called
    if "fmu_path" in args:
        args["fmu_path"] = _fmu_path(source, label, entry, args["fmu_path"])
    try:
        component = cls(name=name, **args)
    except (TypeError, ValueError, OSError, ConfigurationError) as exc:
        raise source.error(label, f"cannot construct {spec} with args {quoted(args)}: "
                           f"{exc}", entry) from exc
    parameters = _mapping(source, label, entry, "parameters")
    try:
        component.set_parameters(**parameters)
    except (KeyError, TypeError, ValueError) as exc:
        raise source.error(f"{label} parameters", str(exc), entry) from exc
    _set_inputs(source, label, entry, component)
    _declare_dependencies(source, label, entry, component)
    for k, indicator in enumerate(_sequence(source, label, entry, "event_indicators")):
        _add_indicator(source, f"{label} event_indicators[{k}]", component, indicator)
    for k, handler in enumerate(_sequence(source, label, entry, "event_handlers")):
        _add_handler(source, f"{label} event_handlers[{k}]", component, handler)
    return component


def _declare_dependencies(source: Source, label: str, entry: dict,
                          component: CoSimComponent) -> None:
    """'dependencies: {output: [inputs]}': what an FMU's outputs depend on where its
    ModelStructure declares nothing."""
    dependencies = _mapping(source, label, entry, "dependencies")
    if not dependencies:
        return
    declare = getattr(component, "declare_dependencies", None)
    if declare is None:
        raise source.error(f"{label} dependencies", "only an FMU component's dependencies can "
                           "be declared (a Python component declares direct_feedthrough)", entry)
    try:
        declare(**dependencies)
    except (ConfigurationError, TypeError) as exc:
        raise source.error(f"{label} dependencies", str(exc), entry) from exc


def _set_inputs(source: Source, label: str, entry: dict, component: CoSimComponent) -> None:
    """`inputs`: start values of inputs, each held until a connection (if any) drives it."""
    inputs = _mapping(source, label, entry, "inputs")
    known = sorted(component.input_specs)
    for name in inputs:
        if name not in known:
            where = " (a parameter: give it under 'parameters')" \
                if name in getattr(component, "parameters", {}) else component.why_no_port(name)
            raise source.error(f"{label} inputs", f"component {component.name!r} has no input "
                               f"{name!r}{where}; inputs: {known or 'none'}", entry)
    try:
        component.set_inputs(inputs)
    except (TypeError, ValueError) as exc:
        raise source.error(f"{label} inputs", str(exc), entry) from exc


def _mapping(source: Source, label: str, entry: dict, key: str) -> dict[str, Any]:
    value = entry.get(key)
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise source.error(label, f"'{key}' must be a mapping, got {kind(value)} "
                           f"{quoted(value)}", entry)
    return dict(value)


def _sequence(source: Source, label: str, entry: dict, key: str) -> list[Any]:
    value = entry.get(key)
    if value is None:
        return []
    if not isinstance(value, list):
        raise source.error(label, f"'{key}' must be a list, got {kind(value)}", entry)
    return value


def _fmu_path(source: Source, label: str, entry: dict, value: Any) -> str:
    """A bundled FMU's name (syssimx.fmus.path), or a path (relative to the description)."""
    if not isinstance(value, str | Path) or not str(value):
        raise source.error(label, f"the FMU must be a name or a path, got {quoted(value)}", entry)
    text = str(value)
    if not text.endswith(".fmu") and "/" not in text:
        from .. import fmus

        try:
            return fmus.path(text)
        except FileNotFoundError as exc:
            raise source.error(label, str(exc), entry) from exc
    path = Path(text).expanduser()
    return str(path if path.is_absolute() else source.directory / path)


def _add_indicator(source: Source, label: str, component: CoSimComponent, entry: Any) -> None:
    """{name, variable, direction}: a zero crossing of an output, evaluated in C."""
    if not isinstance(entry, dict):
        raise source.error(label, "must be a mapping {name, variable, direction}", entry)
    unknown = sorted(set(entry) - set(INDICATOR_KEYS))
    missing = [k for k in ("name", "variable") if k not in entry]
    if unknown or missing:
        raise source.error(label, f"unknown key(s) {unknown}" if unknown else
                           f"missing {missing}; an indicator is {{name, variable, direction}}",
                           entry)
    direction = entry.get("direction", 0)
    if direction in ("falling", "rising", "both"):
        direction = {"falling": -1, "rising": 1, "both": 0}[direction]
    try:
        component.add_event_indicator(str(entry["name"]), variable=str(entry["variable"]),
                                      direction=direction)
    except ConfigurationError as exc:
        raise source.error(label, str(exc), entry) from exc


def _add_handler(source: Source, label: str, component: CoSimComponent, entry: Any) -> None:
    """{input, reinitialize: {parameter: expression of outputs}}."""
    if not isinstance(entry, dict):
        raise source.error(label, "must be a mapping {input, reinitialize}", entry)
    unknown = sorted(set(entry) - set(HANDLER_KEYS))
    if unknown or set(entry) != set(HANDLER_KEYS):
        raise source.error(label, f"unknown key(s) {unknown}" if unknown else
                           f"needs both {list(HANDLER_KEYS)}", entry)
    restart = entry["reinitialize"]
    if not isinstance(restart, dict) or not restart:
        raise source.error(label, "'reinitialize' must map parameters to outputs or numbers, "
                           f"e.g. {{omega0: -omega}}; got {quoted(restart)}", entry)
    try:
        handler = reinitialize_handler(component, restart)
        component.add_event_handler(str(entry["input"]), handler)
    except ConfigurationError as exc:
        raise source.error(label, str(exc), entry) from exc
