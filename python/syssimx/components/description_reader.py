"""A lean reader of FMI 2.0 modelDescription.xml: what syssimx uses, with FMPy's meaning.

fmpy's read_model_description keeps the whole XML tree and a forty-field object per variable
(31 s and 2.6 GB for 10**6 variables). This reader is an lxml parser target: the file streams
through it, no tree is built, and each variable becomes a slotted record of ten fields. The
records and the description keep fmpy's attribute names (`modelVariables`, `valueReference`,
`coSimulation.modelIdentifier`, `declaredType`, `outputs[i].dependencies`, ...)
and its defaults (causality "local", variability "continuous", `initial` from FMI's table), so
code written against fmpy's objects reads these unchanged.

It reads FMI 2.0 only (anything else is refused at the root element). It also refuses, as
FMPy's validation does, what would make syssimx exchange wrong data: two
variables of one name, a value reference outside 0..2**32-1, a start that is not a value of
the variable's type, an undefined declaredType, a ModelStructure index that names no variable.
"""

from __future__ import annotations

import gc
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
_CHUNK = 2**20


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
    """An lxml parser target: builds the description from start and end tags, with no tree
    (attributes arrive as plain dicts). `where` names the file in every error.

    Elements count only at their place in the schema, as fmpy's paths read them
    (fmiModelDescription/CoSimulation, .../ModelVariables/ScalarVariable/Real,
    .../ModelStructure/Outputs/Unknown): whatever a tool writes into annotations is ignored.
    """

    def __init__(self, where: str) -> None:
        self.where = where
        self.description = ModelDescription()
        self.types: dict[str, SimpleType] = {}
        self.names: set[str] = set()
        self.type_attributes: dict[str, str] | None = None  # inside a SimpleType
        self.simple: SimpleType | None = None
        self.variable_attributes: dict[str, str] | None = None  # inside a ScalarVariable
        self.value: tuple[str, dict[str, str]] | None = None  # its type element
        self.depth = 0  # of the element being read; the root is at 1
        self.section = ""  # the current element at depth 2 (ModelVariables, ...)
        self.subsection = ""  # and at depth 3 (ScalarVariable, Outputs, ...)

    def fail(self, problem: str) -> FMUFileError:
        return FMUFileError(f"{self.where}: modelDescription.xml: {problem}")

    # ------------------------------------------------------------ parser target
    def start(self, tag: str, attributes: dict[str, str]) -> None:
        self.depth += 1
        depth = self.depth
        if depth == 4:
            if self.variable_attributes is not None:
                if self.value is None and tag in VALUE_TYPES:
                    self.value = (tag, attributes)
            elif self.type_attributes is not None:
                if self.simple is None:
                    self.simple_type(tag, attributes)
            elif tag == "Unknown" and self.subsection == "Outputs":
                self.unknown(attributes)  # syssimx reads the feedthrough of outputs only
        elif depth == 3:
            self.subsection = tag
            if tag == "ScalarVariable" and self.section == "ModelVariables":
                self.variable_attributes = attributes
                self.value = None
            elif tag == "SimpleType" and self.section == "TypeDefinitions":
                self.type_attributes = attributes
                self.simple = None
        elif depth == 2:
            self.section = tag
            if tag in ("CoSimulation", "ModelExchange"):
                self.interface(tag, attributes)
            elif tag == "DefaultExperiment":
                self.description.defaultExperiment = DefaultExperiment(
                    startTime=attributes.get("startTime"), stopTime=attributes.get("stopTime"),
                    tolerance=attributes.get("tolerance"), stepSize=attributes.get("stepSize"))
        elif depth == 1 and tag == "fmiModelDescription":
            for name in _ROOT_TEXT:
                if name in attributes:
                    setattr(self.description, name, attributes[name])
            version = self.description.fmiVersion
            if version != "2.0":  # before reading variables of another schema
                raise FMUFileError(f"{self.where}: FMI version {version} is not supported "
                                   "(syssimx runs FMI 2.0 Co-Simulation FMUs)")

    def end(self, tag: str) -> None:
        self.depth -= 1
        if self.depth != 2:
            return
        if self.variable_attributes is not None:
            self.variable()
            self.variable_attributes = None
        elif self.type_attributes is not None:
            if self.simple is None:
                raise self.fail(f"SimpleType {self.type_attributes.get('name')!r} has no type "
                                "element")
            self.type_attributes = None

    def close(self) -> ModelDescription:
        if self.description.fmiVersion is None:
            raise self.fail("the root element is not an fmiModelDescription with an "
                            "fmiVersion")
        return self.description

    # ------------------------------------------------------------ elements
    def interface(self, tag: str, attributes: dict[str, str]) -> None:
        cosimulation = tag == "CoSimulation"
        interface = CoSimulation() if cosimulation else ModelExchange()
        interface.modelIdentifier = attributes.get("modelIdentifier")
        flags = _INTERFACE_FLAGS + (_COSIMULATION_FLAGS if cosimulation else ())
        for name in flags:
            setattr(interface, name, _flag(attributes.get(name)))
        if cosimulation:
            self.description.coSimulation = interface
        else:
            self.description.modelExchange = interface

    def simple_type(self, tag: str, attributes: dict[str, str]) -> None:
        type_attributes = self.type_attributes or {}
        self.simple = SimpleType(name=type_attributes.get("name"), type=tag,
                                 description=type_attributes.get("description"),
                                 unit=attributes.get("unit"),
                                 quantity=attributes.get("quantity"))
        self.description.typeDefinitions.append(self.simple)
        self.types[self.simple.name] = self.simple

    def variable(self) -> None:
        attributes = self.variable_attributes or {}
        name = attributes.get("name")
        if name is None:
            raise self.fail(f"a ScalarVariable has no name (valueReference "
                            f"{attributes.get('valueReference')!r})")
        if name in self.names:
            raise self.fail(f"variable {name!r}: the name is not unique")
        self.names.add(name)
        if self.value is None:
            raise self.fail(f"variable {name!r} has no type element ({', '.join(VALUE_TYPES)})")
        kind, typed = self.value
        vr_text = attributes.get("valueReference")
        try:
            vr = int(vr_text)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            raise self.fail(f"variable {name!r}: valueReference {vr_text!r} is not an "
                            "integer") from None
        if not 0 <= vr <= MAX_VALUE_REFERENCE:
            raise self.fail(f"variable {name!r}: valueReference {vr} is outside 0.."
                            f"{MAX_VALUE_REFERENCE}")
        start = typed.get("start")
        if start is not None and not _is_start_of(kind, start.strip()):
            raise self.fail(f"variable {name!r}: start {start!r} is not a {kind} value")
        declared_name = typed.get("declaredType")
        declared = None
        if declared_name is not None:
            declared = self.types.get(declared_name)
            if declared is None:
                raise self.fail(f"variable {name!r}: declaredType {declared_name!r} is not "
                                "defined")
        causality = attributes.get("causality", "local")
        variability = attributes.get("variability", "continuous")
        initial = attributes.get("initial")
        if initial is None:
            try:
                initial = _INITIAL_DEFAULTS[variability][causality]
            except KeyError:
                raise self.fail(f"variable {name!r}: causality={causality!r} with "
                                f"variability={variability!r} is not allowed") from None
        self.description.modelVariables.append(ScalarVariable(
            name, vr, kind, causality, variability, initial, attributes.get("description"),
            typed.get("unit") if kind == "Real" else None, declared, start))

    def unknown(self, attributes: dict[str, str]) -> None:
        variables = self.description.modelVariables
        unknown = Unknown(index=self._index(attributes.get("index")))
        unknown.variable = variables[unknown.index - 1]
        dependencies = attributes.get("dependencies")
        if dependencies is not None:
            unknown.dependencies = [variables[self._index(i) - 1] for i in dependencies.split()]
        self.description.outputs.append(unknown)

    def _index(self, text: str | None) -> int:
        count = len(self.description.modelVariables)
        try:
            index = int(text)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            index = 0
        if not 1 <= index <= count:
            raise self.fail(f"ModelStructure index {text!r} names no variable (there are "
                            f"{count})")
        return index


def read_description(stream: IO[bytes], where: str | Path) -> ModelDescription:
    """Read modelDescription.xml from `stream`; FMUFileError naming `where` if it is unusable.

    No entity is resolved, no DTD loaded and nothing fetched from the network.
    """
    reader = _Reader(str(where))
    parser = etree.XMLParser(target=reader, resolve_entities=False, load_dtd=False,
                             no_network=True)
    # The records form no reference cycles; without the cycle collector's repeated passes
    # over the growing list, 10**6 variables load in an eighth less time.
    collecting = gc.isenabled()
    gc.disable()
    try:
        while chunk := stream.read(_CHUNK):
            parser.feed(chunk)
        return parser.close()
    except etree.XMLSyntaxError as exc:
        raise reader.fail(f"not well-formed XML: {exc}") from exc
    finally:
        if collecting:
            gc.enable()
