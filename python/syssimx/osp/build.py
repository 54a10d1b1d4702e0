"""A System from the records of an OSP system structure: one FMU component per simulator with
its initial values, and the connections libcosim makes of it (the direction of a variable
connection from the variables' causalities, variable groups paired element by element, a
LinearTransformation function as the connection's factor and offset). The algorithm is
Jacobi, as libcosim's fixedStep: every simulator steps on the outputs of the step before."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from urllib.parse import parse_qs, unquote, urlparse

from ..components.fmu import FMUComponent, read_fmu
from ..errors import ConfigurationError
from ..ssp_format.unsupported import Unsupported
from ..system.algorithms import JacobiAlgorithm
from ..system.connection import Connection
from ..system.system import System
from .document import Document, Endpoint, Link, Simulator
from .errors import OSPError
from .groups import Group, find_description, find_group, read_groups

_LOCAL_HOSTS = ("localhost", "127.0.0.1", "::1")


@dataclass(frozen=True)
class PowerBond:
    """Connections a `powerBond` attribute names together (libcosim's ECCO algorithm controls
    the step by the energy they exchange): (source, destination) ports."""

    name: str
    connections: tuple[tuple[tuple[str, str], tuple[str, str]], ...]


def build(document: Document, unsupported: Unsupported,
          proxies_in_process: bool = False) -> tuple[System, list[PowerBond]]:
    """proxies_in_process: a proxy FMU runs in syssimx's process (as it must inside an
    exported FMU, which carries no host process)."""
    name = document.path.parent.name if document.path.name == "OspSystemStructure.xml" \
        else document.path.stem
    system = System(name or document.path.stem)
    system.set_algorithm(JacobiAlgorithm())
    builder = _Builder(document, system, unsupported, proxies_in_process)
    for simulator in document.simulators:
        builder.add(simulator)
    for link in document.links:
        builder.link(link)
    builder.functions()
    bonds = [PowerBond(n, tuple(c)) for n, c in builder.bonds.items()]
    return system, bonds


class _Builder:
    def __init__(self, document: Document, system: System, unsupported: Unsupported,
                 proxies_in_process: bool) -> None:
        self.document = document
        self.system = system
        self.unsupported = unsupported
        self.proxies_in_process = proxies_in_process
        self.groups: dict[str, dict[str, Group]] = {}
        self.signals: dict[tuple[str, str], tuple[Endpoint, str]] = {}
        self.bonds: dict[str, list[tuple[tuple[str, str], tuple[str, str]]]] = {}

    def add(self, simulator: Simulator) -> None:
        path, proxy = self.source(simulator)
        isolated = proxy and self.can_isolate(path, simulator)
        try:
            component = FMUComponent(simulator.name, path, isolated=isolated)
            self.system.add_component(component)
        except ConfigurationError as exc:
            raise OSPError(f"{simulator.where}: {exc}") from exc
        base = self.document.base_step
        if simulator.step_size is not None and simulator.step_size != base:
            self.unsupported.warn("a simulator's own stepSize (libcosim steps it every "
                                  "stepSize/BaseStepSize base steps)",
                                  f"{simulator.where}: every simulator steps at the base step")
        for value in simulator.initial_values:
            _set_start(component, value.variable, value.value, value.where)
        model_name = str(component.info.description.modelName)
        description = find_description(model_name, path, self.document.path)
        if description is not None:
            self.groups[simulator.name] = read_groups(description)

    def can_isolate(self, path: Path, simulator: Simulator) -> bool:
        """Whether a proxy FMU runs in a host process of syssimx's own (isolated=True runs FMI
        2.0 FMUs); another FMI version, or any when proxies run in process, runs in process.
        One warning each way."""
        if self.proxies_in_process:
            self.unsupported.warn("a proxy FMU server (proxyfmu://) in an exported FMU",
                                  f"{simulator.where}: the FMU runs in the exported FMU's "
                                  "process")
            return False
        try:
            version = str(read_fmu(path).description.fmiVersion)
        except ConfigurationError as exc:
            raise OSPError(f"{simulator.where}: {exc}") from exc
        if version == "2.0":
            self.unsupported.warn("a proxy FMU server (proxyfmu://)",
                                  f"{simulator.where}: the FMU runs in a host process of "
                                  "syssimx's own (isolated=True)")
            return True
        self.unsupported.warn(f"a proxy FMU server (proxyfmu://) for an FMI {version} FMU",
                              f"{simulator.where}: the FMU runs in syssimx's process (a host "
                              "process of syssimx's own runs FMI 2.0 FMUs only)")
        return False

    def source(self, simulator: Simulator) -> tuple[Path, bool]:
        """The FMU file, and whether it is a proxy FMU (run in a process of its own)."""
        base = self.document.path.parent
        uri = urlparse(simulator.source)
        if uri.scheme == "proxyfmu":
            if uri.hostname not in _LOCAL_HOSTS:
                raise OSPError(f"{simulator.where}: source {simulator.source!r} is a proxy FMU "
                               f"on the remote host {uri.hostname!r}; syssimx runs FMUs on this "
                               "machine only")
            files = parse_qs(uri.query).get("file")
            if not files:
                raise OSPError(f"{simulator.where}: source {simulator.source!r} names no file")
            return self.existing(base / files[0], simulator), True
        if uri.scheme == "file":
            return self.existing(Path(unquote(uri.path)), simulator), False
        if uri.scheme and len(uri.scheme) > 1:  # not a Windows drive letter
            raise OSPError(f"{simulator.where}: source {simulator.source!r}: the scheme "
                           f"{uri.scheme!r} is not supported (a file path, file: or "
                           "proxyfmu://localhost)")
        return self.existing(base / simulator.source, simulator), False

    def existing(self, path: Path, simulator: Simulator) -> Path:
        if not path.is_file():
            raise OSPError(f"{simulator.where}: source {simulator.source!r} not found "
                           f"({path})")
        return path.resolve()

    def component(self, endpoint: Endpoint, where: str) -> FMUComponent:
        component = self.system.components.get(endpoint.owner)
        if component is None:
            raise OSPError(f"{where}: simulator {endpoint.owner!r} is not among the "
                           f"<Simulators> ({', '.join(self.system.components) or 'none'})")
        return component  # type: ignore[return-value]

    def link(self, link: Link) -> None:
        if link.kind == "VariableConnection":
            self.connect(link.a, link.b, link.where, link.power_bond)
        elif link.kind == "VariableGroupConnection":
            self.connect_groups(link.a, link.b, link.where)
        elif link.kind == "SignalConnection":
            signal, variable = (link.a, link.b) if link.a.function else (link.b, link.a)
            if not signal.function or variable.function:
                raise OSPError(f"{link.where}: a signal connection joins a function's "
                               "<Signal> and a simulator's <Variable>")
            self.signals[(signal.owner, signal.name)] = (variable, link.where)
        else:
            self.unsupported.warn(f"<{link.kind}>", link.where)

    def connect(self, a: Endpoint, b: Endpoint, where: str, bond: str | None = None,
                factor: float = 1.0, offset: float = 0.0) -> None:
        """Connect a and b, from the one that is an output of its FMU."""
        first, second = self.component(a, where), self.component(b, where)
        for component, end in ((first, a), (second, b)):
            if end.name not in component.output_specs and end.name not in component.input_specs:
                raise OSPError(f"{where}: {end.owner!r} ({component.fmu_path}) has no input or "
                               f"output {end.name!r}{component.why_no_port(end.name)}")
        if a.name in first.output_specs and b.name in second.input_specs:
            src, dst = a, b
        elif b.name in second.output_specs and a.name in first.input_specs:
            src, dst = b, a
        else:
            raise OSPError(f"{where}: {a.owner}.{a.name} and {b.owner}.{b.name}: a connection "
                           "joins an output and an input")
        try:
            self.system.add_connection(Connection(src.owner, src.name, dst.owner, dst.name,
                                                  factor, offset))
        except (ConfigurationError, ValueError) as exc:
            raise OSPError(f"{where}: {exc}") from exc
        if bond is not None:
            self.bonds.setdefault(bond, []).append(((src.owner, src.name),
                                                    (dst.owner, dst.name)))

    def connect_groups(self, a: Endpoint, b: Endpoint, where: str) -> None:
        first, second = self.group(a, where), self.group(b, where)
        self.pair(first, second, a.owner, b.owner, where)

    def pair(self, first: Group, second: Group, a: str, b: str, where: str) -> None:
        """Nested groups in order, then the variables in order (as libcosim pairs them)."""
        if len(first.groups) != len(second.groups):
            raise OSPError(f"{where}: groups {a}:{first.name} and {b}:{second.name} hold "
                           f"{len(first.groups)} and {len(second.groups)} groups")
        if len(first.variables) != len(second.variables):
            raise OSPError(f"{where}: groups {a}:{first.name} and {b}:{second.name} hold "
                           f"{len(first.variables)} and {len(second.variables)} variables")
        for inner_a, inner_b in zip(first.groups, second.groups, strict=True):
            self.pair(inner_a, inner_b, a, b, where)
        for x, y in zip(first.variables, second.variables, strict=True):
            self.connect(Endpoint(a, x), Endpoint(b, y), where)

    def group(self, endpoint: Endpoint, where: str) -> Group:
        component = self.component(endpoint, where)
        groups = self.groups.get(endpoint.owner)
        if groups is None:
            raise OSPError(f"{where}: simulator {endpoint.owner!r} has no OSP model description "
                           f"({component.info.description.modelName}_OspModelDescription.xml "
                           "beside its FMU or beside the system structure)")
        group = find_group(groups, endpoint.name)
        if group is None:
            raise OSPError(f"{where}: simulator {endpoint.owner!r} has no variable group "
                           f"{endpoint.name!r} (groups: {', '.join(groups)})")
        return group

    def functions(self) -> None:
        for function in self.document.functions.values():
            if function.kind != "LinearTransformation":
                self.unsupported.warn(f"function <{function.kind}>",
                                      f"{function.where}: its signal connections are left out")
                continue
            into = self.signals.get((function.name, "in"))
            out_of = self.signals.get((function.name, "out"))
            if into is None or out_of is None:
                raise OSPError(f"{function.where}: the function needs a <SignalConnection> "
                               "to its signal 'in' and one from 'out'")
            self.connect(into[0], out_of[0], into[1], factor=function.factor,
                         offset=function.offset)
        for (function_name, signal), (_, where) in self.signals.items():
            if function_name not in self.document.functions:
                raise OSPError(f"{where}: function {function_name!r} (signal {signal!r}) is "
                               "not among the <Functions>")


def _set_start(component: FMUComponent, name: str, value: float | int | bool | str,
               where: str) -> None:
    """An initial value: an input's start or a parameter's value."""
    if name not in component.input_specs and name not in component.info.parameters:
        raise OSPError(f"{where}: {component.name!r} ({component.fmu_path}) has no parameter "
                       f"or input {name!r}{component.why_no_port(name)}")
    try:
        if name in component.input_specs:
            component.set_inputs({name: value})
        else:
            component.set_parameters(**{name: value})
    except (ConfigurationError, TypeError, ValueError) as exc:
        raise OSPError(f"{where}: {exc}") from exc
