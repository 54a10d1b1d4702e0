"""Declarative systems: SysSimX's YAML/JSON system description, built into a System.

    system: {name: Quickstart}
    components:
      - {name: Source, class: "my_models:LinearSource", args: {a: 1.0}, parameters: {}}
      - name: P                                   # syssimx: a bundled FMU by name (or a path)
        fmu: pendulum_cvode
        parameters: {theta0: 0.5}
        event_indicators: [{name: wall_hit, variable: theta, direction: -1}]
        event_handlers: [{input: omega_invert, reinitialize: {theta0: theta, omega0: -omega}}]
    connections: [{src: Source.y, dst: Integrator.u}]      # or {component, port} mappings
    event_connections: [{src: P.wall_hit, dst: P.omega_invert}]
    clock_connections: [{src: Tank.full, dst: Counter.tick}]  # FMI 3.0 clocks (or an indicator)
    algorithm: {type: gauss_seidel}              # jacobi | gauss_seidel | hybrid | ijcsa, options
    run: {t0: 0.0, tf: 5.0, dt: 0.1}

A class is "module.path:Class" (importable, or a .py file beside the description), of syssimx
or of a module the caller allows (component_classes.py: a file never imports anything else).
Every error is a ConfigError naming the file, the entry (and its YAML line) and what is wrong.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from ..errors import ConfigurationError
from .component_classes import allowed_modules as checked_modules
from .config_algorithm import build_algorithm
from .config_components import build_component
from .config_source import ConfigError, Source, kind, quoted, read_file
from .connection import Connection, EventConnection
from .results import SimulationResult
from .system import System

TOP_LEVEL_KEYS = ("system", "components", "connections", "event_connections",
                  "clock_connections", "algorithm", "run")
RUN_KEYS = ("t0", "tf", "dt")

__all__ = ["ConfigError", "build_system", "load_config", "run_from_config"]


def load_config(path: str | Path) -> dict[str, Any]:
    """The description in a YAML file (JSON when the name ends in .json), as a mapping."""
    return read_file(path)


def build_system(config: dict[str, Any] | str | Path, *,
                 allowed_modules: Iterable[str] | None = None) -> System:
    """The System a description (a mapping, or a YAML/JSON file) declares, not initialized.
    `class:` entries may name CoSimComponent subclasses of syssimx and of `allowed_modules`
    (module names; a package allows its submodules): no other module is imported."""
    return _build(*_open(config, allowed_modules))


def _build(source: Source, config: dict[str, Any]) -> System:
    unknown = sorted(set(config) - set(TOP_LEVEL_KEYS))
    if unknown:
        raise source.error("top level", f"unknown key(s) {unknown}; known: "
                           f"{list(TOP_LEVEL_KEYS)}", config)
    system = System(_system_name(source, config))
    undeclared = (config.get("system") or {}).get("undeclared_dependencies", "all")
    try:
        system.undeclared_dependencies = undeclared
    except ConfigurationError as exc:
        raise source.error("system.undeclared_dependencies", str(exc), config["system"]) \
            from exc
    components = config.get("components")
    if not isinstance(components, list) or not components:
        raise source.error("components", "a system needs a non-empty list of components",
                           config)
    for index, entry in enumerate(components):
        component = build_component(source, index, entry)
        try:
            system.add_component(component)
        except ConfigurationError as exc:
            raise source.error(f"components[{index}] {quoted(component.name)}", str(exc),
                               entry) from exc
    for key, connect in (("connections", _connect), ("event_connections", _connect_event),
                         ("clock_connections", _connect_clock)):
        entries = config.get(key) or []
        if not isinstance(entries, list):
            raise source.error(key, f"must be a list, got {kind(entries)}", config)
        for index, entry in enumerate(entries):
            connect(source, f"{key}[{index}]", system, entry)
    if config.get("algorithm") is not None:
        algorithm = build_algorithm(source, config["algorithm"])
        try:
            system.set_algorithm(algorithm)
        except (ConfigurationError, ValueError) as exc:
            raise source.error("algorithm", str(exc), config["algorithm"]) from exc
    return system


def run_from_config(config: dict[str, Any] | str | Path, t0: float | None = None,
                    tf: float | None = None, dt: float | None = None,
                    progress: Any = None, *,
                    allowed_modules: Iterable[str] | None = None) -> SimulationResult:
    """Build, initialize and run a description; t0, tf and dt override its `run` entry.
    allowed_modules: as for build_system."""
    source, config = _open(config, allowed_modules)
    settings = run_settings(source, config, {"t0": t0, "tf": tf, "dt": dt})
    system = _build(source, config)
    system.initialize(settings["t0"])
    options = {} if progress is None else {"progress": progress}
    return system.run(settings["t0"], settings["tf"], settings["dt"], **options)


def run_settings(source: Source, config: dict[str, Any],
                 overrides: dict[str, float | None]) -> dict[str, float]:
    """t0, tf and dt: the `run` entry, each replaced by an override that is not None."""
    run = config.get("run") or {}
    if not isinstance(run, dict):
        raise source.error("run", f"must be a mapping {{t0, tf, dt}}, got {quoted(run)}", config)
    unknown = sorted(set(run) - set(RUN_KEYS))
    if unknown:
        raise source.error("run", f"unknown key(s) {unknown}; known: {list(RUN_KEYS)}", run)
    settings = {**run, **{k: v for k, v in overrides.items() if v is not None}}
    missing = [k for k in RUN_KEYS if k not in settings]
    if missing:
        raise source.error("run", f"missing {missing}: add them to the description's 'run' "
                           "entry or pass them as arguments", run or config)
    for key in RUN_KEYS:
        value = settings[key]
        if isinstance(value, bool) or not isinstance(value, int | float) \
                or not math.isfinite(value):
            raise source.error(f"run.{key}", f"must be a finite number, got {quoted(value)}", run)
        settings[key] = float(value)
    return settings


def _open(config: dict[str, Any] | str | Path, allowed_modules: Iterable[str] | None
          ) -> tuple[Source, dict[str, Any]]:
    try:
        allowed = checked_modules(allowed_modules)
    except ValueError as exc:
        raise ConfigError(str(exc)) from exc
    if isinstance(config, str | Path):
        return Source(Path(config), allowed), read_file(config)
    if not isinstance(config, dict):
        raise ConfigError(f"a system description is a mapping or a file path, got "
                          f"{kind(config)}")
    return Source(None, allowed), config


def _system_name(source: Source, config: dict[str, Any]) -> str:
    system = config.get("system") or {}
    if not isinstance(system, dict) or set(system) - {"name", "undeclared_dependencies"}:
        raise source.error("system", "must be a mapping {name: ..., undeclared_dependencies: "
                           f"all or none}}, got {quoted(system)}", config)
    name = system.get("name", "System")
    if not isinstance(name, str) or not name:
        raise source.error("system.name", f"must be a non-empty string, got {quoted(name)}", system)
    return name


def _endpoint(source: Source, label: str, entry: dict, key: str) -> tuple[str, str]:
    """"Component.port" (split at the first dot) or {component, port}."""
    if key not in entry:
        raise source.error(label, f"missing '{key}'", entry)
    value = entry[key]
    if isinstance(value, dict) and set(value) == {"component", "port"}:
        return str(value["component"]), str(value["port"])
    if isinstance(value, str) and "." in value.strip(".") and value[0] != ".":
        component, port = value.split(".", 1)
        return component, port
    raise source.error(label, f"{key} {quoted(value)} is neither 'Component.port' nor "
                       "{component: ..., port: ...}", entry)


def _checked_entry(source: Source, label: str, entry: Any) -> tuple[str, str, str, str]:
    if not isinstance(entry, dict) or set(entry) != {"src", "dst"}:
        raise source.error(label, f"must be a mapping {{src, dst}}, got {quoted(entry)}", entry)
    return (*_endpoint(source, label, entry, "src"), *_endpoint(source, label, entry, "dst"))


def _connect(source: Source, label: str, system: System, entry: Any) -> None:
    try:
        system.add_connection(Connection(*_checked_entry(source, label, entry)))
    except ConfigError:
        raise
    except ConfigurationError as exc:
        raise source.error(label, str(exc), entry) from exc


def _connect_event(source: Source, label: str, system: System, entry: Any) -> None:
    try:
        system.add_event_connection(EventConnection(*_checked_entry(source, label, entry)))
    except ConfigError:
        raise
    except ConfigurationError as exc:
        raise source.error(label, str(exc), entry) from exc


def _connect_clock(source: Source, label: str, system: System, entry: Any) -> None:
    src_comp, src_port, dst_comp, dst_port = _checked_entry(source, label, entry)
    try:
        system.add_clock_connection(f"{src_comp}.{src_port}", f"{dst_comp}.{dst_port}")
    except ConfigurationError as exc:
        raise source.error(label, str(exc), entry) from exc
