"""OspSystemStructure.xml read into plain records: simulators with their initial values, the
connections (variables, function signals, variable groups, power bonds), the functions, the
times and the algorithm. Nothing here opens an FMU."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .errors import OSPError

NAMESPACE = "http://opensimulationplatform.com/MSMI/OSPSystemStructure"
STRUCTURE_NAME = "OspSystemStructure.xml"
# the top-level elements read; any other is named in a warning
_READ = {"StartTime", "EndTime", "BaseStepSize", "Algorithm", "Simulators", "Functions",
         "Connections", "EccoConfiguration", "Description"}
_TYPES = ("Real", "Integer", "Boolean", "String", "Enumeration")
# XML Schema booleans, as libcosim parses them
_BOOLEANS = {"true": True, "false": False, "1": True, "0": False}


@dataclass(frozen=True)
class InitialValue:
    variable: str
    value: float | int | bool | str
    where: str


@dataclass
class Simulator:
    name: str
    source: str
    step_size: float | None
    initial_values: list[InitialValue]
    where: str


@dataclass(frozen=True)
class Endpoint:
    """A simulator's variable (or variable group), or a function's signal (`function` set)."""

    owner: str
    name: str
    function: bool = False
    causality: str | None = None  # a power bond's variables say theirs


@dataclass(frozen=True)
class Link:
    kind: str  # VariableConnection, SignalConnection, VariableGroupConnection, ...
    a: Endpoint
    b: Endpoint
    power_bond: str | None
    where: str


@dataclass(frozen=True)
class Function:
    kind: str  # LinearTransformation, Sum, VectorSum, ...
    name: str
    factor: float = 1.0
    offset: float = 0.0
    where: str = ""


@dataclass
class Document:
    path: Path
    start_time: float
    end_time: float | None
    base_step: float | None
    algorithm: str
    simulators: list[Simulator]
    functions: dict[str, Function]
    links: list[Link]
    ignored: list[str] = field(default_factory=list)  # top-level elements not read
    ecco: dict[str, float] = field(default_factory=dict)  # <EccoConfiguration>, by element


def structure_file(path: str | Path) -> Path:
    """The system structure file: `path`, or OspSystemStructure.xml in the folder `path`."""
    path = Path(path)
    if path.is_dir():
        path = path / STRUCTURE_NAME
    if not path.is_file():
        raise OSPError(f"{path}: file not found")
    return path


def read_document(path: Path) -> Document:
    """The records of the OSP system structure at `path`; an OSPError names the file and the
    line of what is wrong. No entities are resolved and nothing is fetched."""
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)
    try:
        root = etree.parse(str(path), parser).getroot()
    except (etree.XMLSyntaxError, OSError) as exc:
        raise OSPError(f"{path}: malformed XML: {exc}") from exc
    if root.tag != _tag("OspSystemStructure"):
        raise OSPError(f"{path}: not an OSP system structure: its root element is "
                       f"<{_local(root)}>, not <OspSystemStructure xmlns=\"{NAMESPACE}\">")
    reader = _Reader(path)
    ignored = [f"<{_local(e)}> (line {e.sourceline})" for e in root
               if isinstance(e.tag, str) and _local(e) not in _READ]
    base_step = reader.number(root, "BaseStepSize")
    if base_step is not None and not base_step > 0:
        raise OSPError(f"{path}: <BaseStepSize> {base_step} must be positive")
    algorithm = (reader.text(root, "Algorithm") or "fixedStep").strip()
    if algorithm not in ("fixedStep", "ecco"):
        raise OSPError(f"{path}: <Algorithm> {algorithm!r} is not one of fixedStep, ecco")
    return Document(
        path, reader.number(root, "StartTime") or 0.0, reader.number(root, "EndTime"),
        base_step, algorithm,
        [reader.simulator(e) for e in root.iterfind(f"{_tag('Simulators')}/{_tag('Simulator')}")],
        {f.name: f for f in (reader.function(e) for e in
                             root.iterfind(f"{_tag('Functions')}/*"))},
        [reader.link(e) for e in root.iterfind(f"{_tag('Connections')}/*")
         if isinstance(e.tag, str)], ignored,
        {_local(e): reader.parsed(float, e.text, reader.where(e), _local(e))
         for e in root.iterfind(f"{_tag('EccoConfiguration')}/*") if isinstance(e.tag, str)})


def _tag(name: str) -> str:
    return f"{{{NAMESPACE}}}{name}"


def _local(element: Any) -> str:
    return str(element.tag).rpartition("}")[2]


class _Reader:
    def __init__(self, path: Path) -> None:
        self.path = path

    def where(self, element: Any) -> str:
        name = element.get("name")
        return f"{self.path}: <{_local(element)}{f' {name!r}' if name else ''}> " \
               f"(line {element.sourceline})"

    def text(self, root: Any, name: str) -> str | None:
        element = root.find(_tag(name))
        return None if element is None else (element.text or "")

    def number(self, root: Any, name: str) -> float | None:
        text = self.text(root, name)
        if text is None:
            return None
        return self.parsed(float, text, self.where(root.find(_tag(name))), name)

    def parsed(self, kind: Any, text: str | None, where: str, what: str) -> Any:
        try:
            return kind(text)
        except (TypeError, ValueError, KeyError) as exc:
            raise OSPError(f"{where}: {what} {text!r} is not a {kind.__name__} value"
                           if kind in (float, int) else
                           f"{where}: {what} {text!r} is not a boolean") from exc

    def required(self, element: Any, attribute: str) -> str:
        value = element.get(attribute)
        if value is None:
            raise OSPError(f"{self.where(element)}: the attribute {attribute!r} is missing")
        return str(value)

    def simulator(self, element: Any) -> Simulator:
        step = element.get("stepSize")
        values = [self.initial_value(e) for e in
                  element.iterfind(f"{_tag('InitialValues')}/{_tag('InitialValue')}")]
        return Simulator(self.required(element, "name"), self.required(element, "source"),
                         None if step is None else
                         self.parsed(float, step, self.where(element), "stepSize"),
                         values, self.where(element))

    def initial_value(self, element: Any) -> InitialValue:
        where = f"{self.where(element)} for {element.get('variable')!r}"
        typed = next((e for e in element if isinstance(e.tag, str)), None)
        if typed is None or _local(typed) not in _TYPES:
            raise OSPError(f"{where}: expected one of <{'>, <'.join(_TYPES)}> with a value")
        kind, text = _local(typed), typed.get("value")
        if kind == "Boolean":
            value: float | int | bool | str = self._boolean(text, where)
        else:
            parse = {"Real": float, "Integer": int, "Enumeration": int, "String": str}[kind]
            value = self.parsed(parse, text, where, f"{kind} value")
        return InitialValue(self.required(element, "variable"), value, where)

    def _boolean(self, text: str | None, where: str) -> bool:
        if text is None or text.strip() not in _BOOLEANS:
            raise OSPError(f"{where}: Boolean value {text!r} is not a boolean (true, false, "
                           "1 or 0)")
        return _BOOLEANS[text.strip()]

    def function(self, element: Any) -> Function:
        name = self.required(element, "name")
        factor = element.get("factor", "1.0")
        offset = element.get("offset", "0.0")
        if _local(element) == "LinearTransformation":
            return Function("LinearTransformation", name,
                            self.parsed(float, factor, self.where(element), "factor"),
                            self.parsed(float, offset, self.where(element), "offset"),
                            self.where(element))
        return Function(_local(element), name, where=self.where(element))

    def link(self, element: Any) -> Link:
        ends = [self.endpoint(e) for e in element if isinstance(e.tag, str)]
        if len(ends) != 2:
            raise OSPError(f"{self.where(element)}: a connection has two ends; this one has "
                           f"{len(ends)}")
        return Link(_local(element), ends[0], ends[1], element.get("powerBond"),
                    self.where(element))

    def endpoint(self, element: Any) -> Endpoint:
        if _local(element) in ("Signal", "SignalGroup"):
            return Endpoint(self.required(element, "function"),
                            self.required(element, "name"), True)
        return Endpoint(self.required(element, "simulator"), self.required(element, "name"),
                        False, element.get("causality"))
