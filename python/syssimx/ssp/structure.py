"""The system structure of an SSD, flattened: components with dotted names (Sub.Component),
connections traced through system connectors and signal dictionaries to the component
connectors they join, parameter values, the default experiment.

FMPy's `read_ssd` reads components and connections but not connector types and units, the
default experiment, annotations, .ssd files outside an archive, or the LinearTransformation of
a connection (it looks for it in the wrong namespace); so this walks the XML itself.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .archive import Package, resolve
from .documents import NS, element_label, local_name, parse
from .errors import SSPError
from .experiment import Experiment
from .parameters import ParameterValue, read_bindings
from .unsupported import Unsupported

FMU_TYPE = "application/x-fmu-sharedlibrary"
OSP_STEP = "FixedStepAlgorithm"  # the Open Simulation Platform's annotation for a fixed step
_MAP_TRANSFORMATIONS = ("BooleanMappingTransformation", "IntegerMappingTransformation",
                        "EnumerationMappingTransformation")


@dataclass(frozen=True)
class Connector:
    name: str
    kind: str
    type: str | None  # Real, Integer, Boolean, String, Enumeration; None when not declared
    unit: str | None
    label: str  # for errors: the element and its line


@dataclass
class ComponentEntry:
    path: str  # dotted: the names of the enclosing systems below the root, then its own
    source: Path
    connectors: dict[str, Connector]
    label: str
    parameters: list[ParameterValue] = field(default_factory=list)


@dataclass(frozen=True)
class ConnectionEntry:
    """src drives dst, both (component path, connector name); dst = factor * src + offset
    after the unit conversion (none when convert_units is false)."""

    src: tuple[str, str]
    dst: tuple[str, str]
    factor: float
    offset: float
    convert_units: bool
    label: str


@dataclass
class Structure:
    name: str
    components: dict[str, ComponentEntry]
    connections: list[ConnectionEntry]
    experiment: Experiment
    units: dict[str, Any]


@dataclass(frozen=True)
class _Link:
    start: tuple[str, str]
    factor: float
    offset: float
    convert_units: bool
    label: str


def read_structure(package: Package, unsupported: Unsupported) -> Structure:
    from .units import read_units

    root = parse(package.ssd, "ssd", package.shown(package.ssd))
    walk = _Walk(package, unsupported)
    system = root.find("ssd:System", NS)
    walk.system(system, "", 0)
    _warn_annotations(root, package, unsupported)
    for parameters, owner, _ in sorted(walk.bindings, key=lambda b: -b[2]):
        walk.assign(parameters, owner)  # outer systems last: their values win
    return Structure(root.get("name") or system.get("name"), walk.components,
                     walk.connections(), _experiment(root, package), read_units(root))


class _Walk:
    def __init__(self, package: Package, unsupported: Unsupported) -> None:
        self.package = package
        self.unsupported = unsupported
        self.components: dict[str, ComponentEntry] = {}
        self.links: dict[tuple[str, str], _Link] = {}
        self.bindings: list[tuple[list[ParameterValue], str | None, int]] = []
        self.dictionaries: dict[str, str] = {}  # reference element path -> dictionary key

    def where(self, element: Any) -> str:
        return f"{self.package.shown(self.package.ssd)}: {element_label(element)}"

    def system(self, system: Any, path: str, depth: int) -> None:
        self.bindings.append((read_bindings(system, self.package, self.unsupported), path,
                              depth))
        for dictionary in system.iterfind("ssd:SignalDictionaries/ssd:SignalDictionary", NS):
            if dictionary.get("source") is not None:
                path = resolve(self.package, dictionary.get("source"), element_label(dictionary))
                parse(path, "ssb", self.package.shown(path))
        for element in system.iterfind("ssd:Elements/*", NS):
            name = element.get("name")
            child = f"{path}.{name}" if path else name
            kind = local_name(element)
            if kind == "System":
                self.system(element, child, depth + 1)
            elif kind == "SignalDictionaryReference":
                self.dictionaries[child] = f"#dictionary {element.get('dictionary')}"
            elif element.get("type", FMU_TYPE) != FMU_TYPE:
                self.unsupported.warn(f"component type {element.get('type')!r}",
                                      self.where(element))
            else:
                self.component(element, child, depth + 1)
        for connection in system.iterfind("ssd:Connections/ssd:Connection", NS):
            self.connection(connection, path)

    def component(self, element: Any, path: str, depth: int) -> None:
        if element.get("implementation") == "ModelExchange":
            self.unsupported.warn("implementation 'ModelExchange'",
                                  f"{self.where(element)}, run as Co-Simulation")
        source = resolve(self.package, element.get("source"), element_label(element))
        connectors = {}
        for connector in element.iterfind("ssd:Connectors/ssd:Connector", NS):
            if connector.get("kind") not in ("input", "output", "parameter"):
                self.unsupported.warn(f"connector kind {connector.get('kind')!r} on a "
                                      "component", self.where(connector))
                continue
            typed = next(iter(connector.iterfind("ssc:*", NS)), None)
            connectors[connector.get("name")] = Connector(
                connector.get("name"), connector.get("kind"),
                None if typed is None else local_name(typed),
                None if typed is None else typed.get("unit"), self.where(connector))
        self.components[path] = ComponentEntry(path, source, connectors, self.where(element))
        self.bindings.append((read_bindings(element, self.package, self.unsupported), path,
                              depth))

    def endpoint(self, system: str, element: str | None, connector: str) -> tuple[str, str]:
        if element is None:
            return system, connector
        path = f"{system}.{element}" if system else element
        return self.dictionaries.get(path, path), connector

    def connection(self, connection: Any, system: str) -> None:
        label = self.where(connection)
        for name in _MAP_TRANSFORMATIONS:
            if connection.find(f"ssc:{name}", NS) is not None:
                self.unsupported.warn(f"ssc:{name}", label)
        linear = connection.find("ssc:LinearTransformation", NS)
        end = self.endpoint(system, connection.get("endElement"), connection.get("endConnector"))
        if end in self.links:
            raise SSPError(f"{label}: {'.'.join(end)} is already driven by "
                           f"{'.'.join(self.links[end].start)}")
        self.links[end] = _Link(
            self.endpoint(system, connection.get("startElement"),
                          connection.get("startConnector")),
            float(linear.get("factor", 1.0)) if linear is not None else 1.0,
            float(linear.get("offset", 0.0)) if linear is not None else 0.0,
            connection.get("suppressUnitConversion", "false") not in ("true", "1"), label)

    def connections(self) -> list[ConnectionEntry]:
        """Each component input connector with the component output that drives it, through
        any chain of system connectors and signal dictionary entries."""
        entries = []
        for end, link in self.links.items():
            if end[0] not in self.components:
                continue
            connector = self.components[end[0]].connectors.get(end[1])
            if connector is not None and connector.kind == "parameter":
                self.unsupported.warn("a connection to a parameter connector", link.label)
                continue
            driver = self.driver(link)
            if driver is None:
                self.unsupported.warn("a connection from an unconnected system input",
                                      f"{link.label}, {'.'.join(end)} keeps its start value")
                continue
            entries.append(ConnectionEntry(driver.start, end, driver.factor, driver.offset,
                                           driver.convert_units, link.label))
        return entries

    def driver(self, link: _Link) -> _Link | None:
        """`link` followed back to a component connector, the transformations composed;
        None when the chain starts at an input of the root system or an undriven entry."""
        while link.start[0] not in self.components:
            outer = self.links.get(link.start)
            if outer is None:
                return None
            link = _Link(outer.start, link.factor * outer.factor,
                         link.factor * outer.offset + link.offset,
                         link.convert_units and outer.convert_units, link.label)
        return link

    def assign(self, parameters: list[ParameterValue], owner: str | None) -> None:
        """Values bound at a component are its own; values bound at a system name a component
        below it by its dotted path (the longest that matches) and then the parameter."""
        for value in parameters:
            if owner in self.components:
                self.components[owner].parameters.append(value)
                continue
            full = f"{owner}.{value.name}" if owner else value.name
            match = max((p for p in self.components if full.startswith(p + ".")), key=len,
                        default=None)
            if match is None:
                raise SSPError(f"{value.where}: parameter {value.name!r} names no component of "
                               f"system {owner or '(root)'!r}")
            self.components[match].parameters.append(
                ParameterValue(full[len(match) + 1:], value.value, value.unit, value.where))


def _experiment(root: Any, package: Package) -> Experiment:
    experiment = root.find("ssd:DefaultExperiment", NS)
    if experiment is None:
        return Experiment()
    step = None
    for annotation in experiment.iterfind("ssd:Annotations/ssc:Annotation", NS):
        for element in annotation.iter():
            if local_name(element) == OSP_STEP and element.get("baseStepSize") is not None:
                try:
                    step = float(element.get("baseStepSize"))
                except ValueError as exc:
                    raise SSPError(f"{package.shown(package.ssd)}: {element_label(element)}: "
                                   f"baseStepSize {element.get('baseStepSize')!r} is not a "
                                   "number") from exc
    start, stop = experiment.get("startTime"), experiment.get("stopTime")
    return Experiment(float(start) if start is not None else None,
                      float(stop) if stop is not None else None, step)


def _warn_annotations(root: Any, package: Package, unsupported: Unsupported) -> None:
    for annotation in root.iter(f"{{{NS['ssc']}}}Annotation"):
        known = any(local_name(e) == OSP_STEP for e in annotation.iter())
        if not known:
            unsupported.warn(f"annotation type {annotation.get('type')!r}",
                             f"{package.shown(package.ssd)}: {element_label(annotation)}")
