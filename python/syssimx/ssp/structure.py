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

from ..ssp_format.archive import Package, resolve
from ..ssp_format.documents import NS, element_label, local_name, parse
from ..ssp_format.errors import SSPError
from ..ssp_format.experiment import Experiment
from ..ssp_format.unsupported import Unsupported
from .parameters import ParameterValue, read_bindings

FMU_TYPE = "application/x-fmu-sharedlibrary"
OSP_STEP = "FixedStepAlgorithm"  # the Open Simulation Platform's annotation for a fixed step
OMS_STEP = "FixedStepMaster"  # OMSimulator's
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
    interface: str = "auto"  # the FMU interface the SSD's implementation attribute asks for
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


# the SSD's implementation attribute of a component, as FMUComponent's interface
_INTERFACES = {"ModelExchange": "model-exchange", "CoSimulation": "co-simulation",
               "any": "auto"}


def read_structure(package: Package, unsupported: Unsupported) -> Structure:
    from .units import read_units

    root = parse(package.ssd, "ssd", package.shown(package.ssd), unsupported)
    walk = _Walk(package, unsupported)
    system = root.find("ssd:System", NS)
    walk.system(system, "", 0)
    experiment, annotations_read = _experiment(root, package)
    _warn_annotations(root, package, unsupported, annotations_read)
    for parameters, owner, _ in sorted(walk.bindings, key=lambda b: -b[2]):
        walk.assign(parameters, owner)  # outer systems last: their values win
    return Structure(root.get("name") or system.get("name"), walk.components,
                     walk.connections(), experiment, read_units(root))


class _Walk:
    def __init__(self, package: Package, unsupported: Unsupported) -> None:
        self.package = package
        self.unsupported = unsupported
        self.components: dict[str, ComponentEntry] = {}
        self.systems: set[str] = set()
        self.left_out: set[str] = set()  # elements syssimx does not read (non-FMU components)
        self.system_connectors: dict[tuple[str, str], str] = {}  # (system, name) -> kind
        self.connector_values: dict[tuple[str, str], ParameterValue] = {}
        self.links: dict[tuple[str, str], _Link] = {}
        self.bindings: list[tuple[list[ParameterValue], str, int]] = []
        self.dictionaries: dict[str, str] = {}  # reference element path -> dictionary key

    def where(self, element: Any) -> str:
        return f"{self.package.shown(self.package.ssd)}: {element_label(element)}"

    def system(self, system: Any, path: str, depth: int) -> None:
        self.systems.add(path)
        for connector in system.iterfind("ssd:Connectors/ssd:Connector", NS):
            self.system_connectors[(path, connector.get("name"))] = connector.get("kind")
        self.bindings.append((read_bindings(system, self.package, self.unsupported), path,
                              depth))
        for dictionary in system.iterfind("ssd:SignalDictionaries/ssd:SignalDictionary", NS):
            if dictionary.get("source") is not None:
                source = resolve(self.package, dictionary.get("source"),
                                 element_label(dictionary))
                parse(source, "ssb", self.package.shown(source), self.unsupported)
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
                self.left_out.add(child)
            else:
                self.component(element, child, depth + 1)
        for connection in system.iterfind("ssd:Connections/ssd:Connection", NS):
            self.connection(connection, path)

    def component(self, element: Any, path: str, depth: int) -> None:
        implementation = element.get("implementation", "any")
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
        self.components[path] = ComponentEntry(path, source, connectors, self.where(element),
                                               _INTERFACES.get(implementation, "auto"))
        self.bindings.append((read_bindings(element, self.package, self.unsupported), path,
                              depth))

    def endpoint(self, system: str, element: str | None, connector: str) -> tuple[str, str]:
        if not element:  # absent or "" (as OMSimulator writes it): the system's own connector
            return system, connector
        path = f"{system}.{element}" if system else element
        return self.dictionaries.get(path, path), connector

    def connection(self, connection: Any, system: str) -> None:
        label = self.where(connection)
        ends = []
        for role in ("start", "end"):
            element, name = connection.get(f"{role}Element"), connection.get(f"{role}Connector")
            endpoint = self.endpoint(system, element, name)
            problem = self.unknown(endpoint, element, name, role, system)
            if problem:
                self.unsupported.ignore(f"{label}: {problem}", "the connection is left out")
                return
            ends.append(endpoint)
        for name in _MAP_TRANSFORMATIONS:
            if connection.find(f"ssc:{name}", NS) is not None:
                self.unsupported.warn(f"ssc:{name}", label)
        linear = connection.find("ssc:LinearTransformation", NS)
        start, end = ends
        if end in self.links:
            raise SSPError(f"{label}: {_named(end)} is already driven by "
                           f"{_named(self.links[end].start)}")
        self.links[end] = _Link(
            start, float(linear.get("factor", 1.0)) if linear is not None else 1.0,
            float(linear.get("offset", 0.0)) if linear is not None else 0.0,
            connection.get("suppressUnitConversion", "false") not in ("true", "1"), label)

    def unknown(self, endpoint: tuple[str, str], element: str | None, connector: str,
                role: str, system: str) -> str:
        """What an end of a connection names that does not exist ("" when it exists; a
        component's connectors are checked against its FMU when the system is built)."""
        owner = f"system {system!r}" if system else "the root system"
        if endpoint[0] in self.components or endpoint[0].startswith("#dictionary"):
            return ""
        if endpoint[0] in self.left_out:
            return f"{role}Element {element!r} is a component syssimx leaves out"
        if element and endpoint[0] not in self.systems:
            return f"{role}Element {element!r} names no element of {owner}"
        if endpoint not in self.system_connectors:
            named = f"system {endpoint[0]!r}" if endpoint[0] else "the root system"
            return f"{role}Connector {connector!r} names no connector of {named}"
        return ""

    def connections(self) -> list[ConnectionEntry]:
        """Each component input connector with the component output that drives it, through
        any chain of system connectors and signal dictionary entries. A component connector
        driven by a system connector that carries a value (and nothing drives) gets that
        value: a parameter's value, or an input's start."""
        entries = []
        for end, link in self.links.items():
            if end[0] not in self.components:
                self.driver(end, link)  # only to find a cycle that no component is on
                continue  # a system connector: followed from the component connectors it drives
            connector = self.components[end[0]].connectors.get(end[1])
            driver, bound = self.driver(end, link)
            if driver.start[0] in self.components:
                if connector is not None and connector.kind == "parameter":
                    self.unsupported.warn("a connection from an output to a parameter "
                                          "connector", link.label)
                    continue
                entries.append(ConnectionEntry(driver.start, end, driver.factor,
                                               driver.offset, driver.convert_units,
                                               link.label))
            elif bound is not None:
                self.components[end[0]].parameters.append(bound)
            else:
                self.unsupported.warn("a connection from a system connector that has no "
                                      "value and nothing drives",
                                      f"{link.label}, {_named(end)} keeps its start value")
        return entries

    def driver(self, end: tuple[str, str], link: _Link) -> tuple[_Link, ParameterValue | None]:
        """`link` followed back through system connectors, the transformations composed,
        to a component connector or to a system connector nothing drives; and the value
        bound to the outermost connector on the way that has one (its connection drives all
        the others), transformed, for `end`."""
        bound: ParameterValue | None = None
        visited = [link.start]
        while link.start[0] not in self.components:
            value = self.connector_values.get(link.start)
            if value is not None:
                number = link.factor * value.value + link.offset \
                    if isinstance(value.value, float) else value.value
                bound = ParameterValue(end[1], number, value.unit, value.where,
                                       value.definition)
            outer = self.links.get(link.start)
            if outer is None:
                break
            if outer.start in visited:
                cycle = [*visited[visited.index(outer.start):], outer.start]
                raise SSPError(f"{outer.label}: the system connectors "
                               f"{' -> '.join(reversed([_named(c) for c in cycle]))} form a "
                               "cycle: nothing drives them")
            visited.append(outer.start)
            link = _Link(outer.start, link.factor * outer.factor,
                         link.factor * outer.offset + link.offset,
                         link.convert_units and outer.convert_units, link.label)
        return link, bound

    def assign(self, parameters: list[ParameterValue], owner: str) -> None:
        """Values bound at a component are its own; values bound at a system name a connector
        of that system or of one below it, or a component below it by its dotted path (the
        longest that matches) and then the parameter."""
        for value in parameters:
            if owner in self.components:
                self.components[owner].parameters.append(value)
                continue
            full = f"{owner}.{value.name}" if owner else value.name
            system, _, connector = full.rpartition(".")
            if (system, connector) in self.system_connectors:
                self.connector_values[(system, connector)] = value
                continue
            match = max((p for p in self.components if full.startswith(p + ".")), key=len,
                        default=None)
            if match is None:
                self.unsupported.ignore(f"{value.where}: parameter {value.name!r} names no "
                                        f"component or connector of "
                                        f"{f'system {owner!r}' if owner else 'the root system'}",
                                        "the value is ignored")
                continue
            self.components[match].parameters.append(
                ParameterValue(full[len(match) + 1:], value.value, value.unit, value.where,
                               value.definition))


def _named(endpoint: tuple[str, str]) -> str:
    """A connector as a user reads it: Element.connector, or the root system's own name."""
    return ".".join(endpoint) if endpoint[0] else endpoint[1]


def _experiment(root: Any, package: Package) -> tuple[Experiment, list[Any]]:
    """The default experiment, and the annotations it was read from. The step comes from a
    tool's annotation: the Open Simulation Platform's FixedStepAlgorithm baseStepSize in the
    default experiment, else OMSimulator's FixedStepMaster stepSize on the root system."""
    experiment = root.find("ssd:DefaultExperiment", NS)
    places = [(experiment, OSP_STEP, "baseStepSize"),
              (root.find("ssd:System", NS), OMS_STEP, "stepSize")]
    for parent, name, attribute in places:
        if parent is None:
            continue
        for annotation in parent.iterfind("ssd:Annotations/ssc:Annotation", NS):
            for element in annotation.iter():
                if local_name(element) == name and element.get(attribute) is not None:
                    return Experiment(*_times(experiment),
                                      _number(element, attribute, package)), [annotation]
    return Experiment(*_times(experiment)), []


def _times(experiment: Any) -> tuple[float | None, float | None]:
    if experiment is None:
        return None, None
    start, stop = experiment.get("startTime"), experiment.get("stopTime")
    return (float(start) if start is not None else None,
            float(stop) if stop is not None else None)


def _number(element: Any, attribute: str, package: Package) -> float:
    try:
        return float(element.get(attribute))
    except ValueError as exc:
        raise SSPError(f"{package.shown(package.ssd)}: {element_label(element)}: {attribute} "
                       f"{element.get(attribute)!r} is not a number") from exc


def _warn_annotations(root: Any, package: Package, unsupported: Unsupported,
                      read: list[Any]) -> None:
    for annotation in root.iter(f"{{{NS['ssc']}}}Annotation"):
        if annotation not in read:
            unsupported.warn(f"annotation type {annotation.get('type')!r}",
                             f"{package.shown(package.ssd)}: {element_label(annotation)}")
