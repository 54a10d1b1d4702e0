"""A lean reader of FMI 2.0 modelDescription.xml: what syssimx uses, with FMPy's meaning.

fmpy's read_model_description keeps the whole XML tree and a forty-field object per variable
(31 s and 2.6 GB for 10**6 variables). This reader streams the file with lxml's iterparse,
drops each variable's element once read and keeps a slotted record of eleven fields per
variable. The records and the description keep fmpy's attribute names (`modelVariables`,
`coSimulation.modelIdentifier`, `valueReference`, `declaredType`, `outputs[i].dependencies`, ...)
and its defaults (causality "local", variability "continuous", `initial` from FMI's table), so
code written against fmpy's objects reads these unchanged.

It also refuses, as FMPy's validation does, what would make syssimx exchange wrong data: two
variables of one name, a value reference outside 0..2**32-1, a start that is not a value of
the variable's type, an undefined declaredType, a ModelStructure index that names no variable.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import IO

from fmpy.model_description import (
    CoSimulation,
    DefaultExperiment,
    ModelDescription,
    ModelExchange,
    SimpleType,
    Unknown,
)
from lxml import etree

from ..errors import FMUFileError

VALUE_TYPES = ("Real", "Integer", "Boolean", "String", "Enumeration")
MAX_VALUE_REFERENCE = 2**32 - 1  # fmi2ValueReference is an unsigned int

# FMI 2.0, section 2.2.7: the initial a variable has when it declares none.
_INITIAL_DEFAULTS = {
    "constant": {"output": "exact", "local": "exact"},
    "fixed": {"parameter": "exact", "calculatedParameter": "calculated", "local": "calculated"},
    "tunable": {"parameter": "exact", "calculatedParameter": "calculated", "local": "calculated"},
    "discrete": {"input": "exact", "output": "calculated", "local": "calculated"},
    "continuous": {"input": "exact", "output": "calculated", "local": "calculated",
                   "independent": None},
}

_INTERFACE_FLAGS = ("needsExecutionTool", "canBeInstantiatedOnlyOncePerProcess",
                    "canNotUseMemoryManagementFunctions", "canGetAndSetFMUstate",
                    "canSerializeFMUstate", "providesDirectionalDerivative")
_COSIMULATION_FLAGS = ("canHandleVariableCommunicationStepSize", "canInterpolateInputs",
                       "canRunAsynchronuously")
_ROOT_TEXT = ("fmiVersion", "modelName", "guid", "description", "author", "version", "copyright",
              "license", "generationTool", "generationDateAndTime", "variableNamingConvention")
_EVENT_TAGS = ("fmiModelDescription", "CoSimulation", "ModelExchange", "DefaultExperiment",
               "SimpleType", "ScalarVariable", "Unknown")


@dataclass(slots=True, eq=False)
class ScalarVariable:
    """One ScalarVariable, with fmpy's attribute names; `start` is the text of the XML."""

    name: str
    valueReference: int  # noqa: N815 (fmpy's names)
    type: str
    causality: str
    variability: str
    initial: str | None
    description: str | None
    unit: str | None
    declaredType: SimpleType | None  # noqa: N815
    start: str | None
    sourceline: int | None


def _flag(text: str | None) -> bool:
    return text in ("true", "1")


def _is_start_of(kind: str, text: str) -> bool:
    """Whether `text` is a value of an FMI 2.0 variable of type `kind` (xs:double, xs:int, ...)."""
    if kind == "Real":
        try:
            float(text)
        except ValueError:
            return False
        return True
    if kind in ("Integer", "Enumeration"):
        try:
            value = int(text)
        except ValueError:
            return False
        return -(2**31) <= value < 2**31
    if kind == "Boolean":
        return text in ("true", "false", "1", "0")
    return True


class _Reader:
    """The state of one streaming read; `where` names the file in every error."""

    def __init__(self, where: str) -> None:
        self.where = where
        self.description = ModelDescription()
        self.types: dict[str, SimpleType] = {}
        self.names: set[str] = set()

    def fail(self, problem: str, line: int | None = None) -> FMUFileError:
        at = f" (line {line})" if line is not None else ""
        return FMUFileError(f"{self.where}: modelDescription.xml{at}: {problem}")

    def root(self, element: etree._Element) -> None:
        for name in _ROOT_TEXT:
            value = element.get(name)
            if value is not None:
                setattr(self.description, name, value)

    def interface(self, element: etree._Element) -> None:
        cosimulation = element.tag == "CoSimulation"
        interface = CoSimulation() if cosimulation else ModelExchange()
        interface.modelIdentifier = element.get("modelIdentifier")
        flags = _INTERFACE_FLAGS + (_COSIMULATION_FLAGS if cosimulation else ())
        for name in flags:
            setattr(interface, name, _flag(element.get(name)))
        if cosimulation:
            self.description.coSimulation = interface
        else:
            self.description.modelExchange = interface

    def default_experiment(self, element: etree._Element) -> None:
        self.description.defaultExperiment = DefaultExperiment(
            startTime=element.get("startTime"), stopTime=element.get("stopTime"),
            tolerance=element.get("tolerance"), stepSize=element.get("stepSize"))

    def simple_type(self, element: etree._Element) -> None:
        if len(element) == 0:
            raise self.fail(f"SimpleType {element.get('name')!r} has no type element",
                            element.sourceline)
        first = element[0]
        simple = SimpleType(name=element.get("name"), type=first.tag,
                            description=element.get("description"), unit=first.get("unit"),
                            quantity=first.get("quantity"))
        self.description.typeDefinitions.append(simple)
        self.types[simple.name] = simple

    def variable(self, element: etree._Element) -> None:
        line = element.sourceline
        name = element.get("name")
        if name is None:
            raise self.fail("a ScalarVariable has no name", line)
        if name in self.names:
            raise self.fail(f"variable {name!r}: the name is not unique", line)
        self.names.add(name)
        value = next((child for child in element if child.tag in VALUE_TYPES), None)
        if value is None:
            raise self.fail(f"variable {name!r} has no type element "
                            f"({', '.join(VALUE_TYPES)})", line)
        kind = value.tag
        vr_text = element.get("valueReference")
        try:
            vr = int(vr_text)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            raise self.fail(f"variable {name!r}: valueReference {vr_text!r} is not an "
                            "integer", line) from None
        if not 0 <= vr <= MAX_VALUE_REFERENCE:
            raise self.fail(f"variable {name!r}: valueReference {vr} is outside 0.."
                            f"{MAX_VALUE_REFERENCE}", line)
        start = value.get("start")
        if start is not None and not _is_start_of(kind, start.strip()):
            raise self.fail(f"variable {name!r}: start {start!r} is not a {kind} value", line)
        declared_name = value.get("declaredType")
        declared = None
        if declared_name is not None:
            declared = self.types.get(declared_name)
            if declared is None:
                raise self.fail(f"variable {name!r}: declaredType {declared_name!r} is not "
                                "defined", line)
        causality = element.get("causality", "local")
        variability = element.get("variability", "continuous")
        initial = element.get("initial")
        if initial is None:
            try:
                initial = _INITIAL_DEFAULTS[variability][causality]
            except KeyError:
                raise self.fail(f"variable {name!r}: causality={causality!r} with "
                                f"variability={variability!r} is not allowed", line) from None
        self.description.modelVariables.append(ScalarVariable(
            name, vr, kind, causality, variability, initial, element.get("description"),
            value.get("unit") if kind == "Real" else None, declared, start, line))

    def unknown(self, element: etree._Element) -> None:
        section = element.getparent().tag
        if section != "Outputs":
            return  # syssimx reads the feedthrough of outputs only
        variables = self.description.modelVariables
        line = element.sourceline
        unknown = Unknown(index=self._index(element.get("index"), line), sourceline=line)
        unknown.variable = variables[unknown.index - 1]
        dependencies = element.get("dependencies")
        if dependencies is not None:
            unknown.dependencies = [variables[self._index(i, line) - 1]
                                    for i in dependencies.split()]
        self.description.outputs.append(unknown)

    def _index(self, text: str | None, line: int | None) -> int:
        count = len(self.description.modelVariables)
        try:
            index = int(text)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            index = 0
        if not 1 <= index <= count:
            raise self.fail(f"ModelStructure index {text!r} names no variable (there are "
                            f"{count})", line)
        return index


def read_description(stream: IO[bytes], where: str | Path) -> ModelDescription:
    """Read modelDescription.xml from `stream`; FMUFileError naming `where` if it is unusable.

    No entity is resolved, no DTD loaded and nothing fetched from the network.
    """
    reader = _Reader(str(where))
    handlers = {"fmiModelDescription": reader.root, "CoSimulation": reader.interface,
                "ModelExchange": reader.interface, "DefaultExperiment": reader.default_experiment,
                "SimpleType": reader.simple_type, "ScalarVariable": reader.variable,
                "Unknown": reader.unknown}
    events = etree.iterparse(stream, events=("end",), tag=_EVENT_TAGS, resolve_entities=False,
                             load_dtd=False, no_network=True)
    try:
        for _, element in events:
            handlers[element.tag](element)
            if element.tag != "fmiModelDescription":
                # read: free the element and its siblings before it
                element.clear()
                while element.getprevious() is not None:
                    del element.getparent()[0]
    except etree.XMLSyntaxError as exc:
        raise reader.fail(f"not well-formed XML: {exc}") from exc
    description = reader.description
    if description.fmiVersion is None:
        raise reader.fail("the root element is not an fmiModelDescription with an fmiVersion")
    return description
