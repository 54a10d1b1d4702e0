"""A lean reader of FMI 2.0 modelDescription.xml: what syssimx uses, with FMPy's meaning.

fmpy's read_model_description keeps the whole XML tree and a forty-field object per variable
(31 s and 2.6 GB for 10**6 variables). Here the engine reads the text in one pass into compact
arrays (ssx_md_read, which also checks it: see syssimx_engine.h), and this module makes fmpy's
objects of the few elements around the variables. The variables stay in the engine's arrays,
behind a VariableTable that makes a ScalarVariable for the one asked for. The objects keep
fmpy's attribute names (`modelVariables`, `valueReference`, `coSimulation.modelIdentifier`,
`declaredType`, `outputs[i].dependencies`, ...) and its defaults (causality "local",
variability "continuous", `initial` from FMI's table), so code written against fmpy's objects
reads these unchanged.

The engine reads UTF-8 (description.py decodes any other encoding first) and stops at the root
element of another FMI version: description.py then hands the archive to that version's
standard (standards.py). It also refuses, as
FMPy's validation does, what would make syssimx exchange wrong data: two variables of one
name, a value reference outside 0..2**32-1, a start that is not a value of the variable's type,
an undefined declaredType, a ModelStructure index that names no variable.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..engine import ffi, lib
from ..errors import FMUFileError
from .variable_table import VariableTable, words

# declared event indicators of one FMU: each costs the engine memory before the first step
MAX_EVENT_INDICATORS = 1_000_000

# fmpy's classes are imported by the first read, not with syssimx: importing fmpy costs about as
# much as importing the rest of syssimx.
if TYPE_CHECKING:
    from fmpy.model_description import ModelDescription, Unknown

MAX_VALUE_REFERENCE = 2**32 - 1  # fmi2ValueReference is an unsigned int, as the engine reads it

_INTERFACE_FLAGS = ("needsExecutionTool", "canBeInstantiatedOnlyOncePerProcess",
                    "canNotUseMemoryManagementFunctions", "canGetAndSetFMUstate",
                    "canSerializeFMUstate", "providesDirectionalDerivative")
_COSIMULATION_FLAGS = ("canHandleVariableCommunicationStepSize", "canInterpolateInputs",
                       "canRunAsynchronuously")
_ROOT_TEXT = ("fmiVersion", "modelName", "guid", "description", "author", "version", "copyright",
              "license", "generationTool", "generationDateAndTime", "variableNamingConvention")


def engine_description(text: bytes | bytearray, where: str | Path) -> Any:
    """The engine's reading of the UTF-8 modelDescription `text` (ssx_md, freed with it). Check
    its error.problem: a description of another FMI version stops at the root element.

    No entity but XML's five predefined ones is resolved, no DTD accepted and nothing fetched
    from the network.
    """
    engine = lib()
    md = engine.ssx_md_read(ffi.from_buffer(text), len(text))
    if md == ffi.NULL:
        raise MemoryError(f"{where}: no memory to read modelDescription.xml")
    return ffi.gc(md, engine.ssx_md_free)


def declared_version(md: Any) -> str | None:
    """The fmiVersion the root element declares (None: none)."""
    if md.error.problem == lib().SSX_MD_NOT_FMI2:
        return _optional(md.error.text)
    for k in range(md.attribute_count):
        kept = md.attributes[k]
        if (_text(md, kept.element), _text(md, kept.name)) == ("fmiModelDescription",
                                                                "fmiVersion"):
            return _text(md, kept.value)
    return None


def _text(md: Any, offset: int) -> str | None:
    return ffi.string(md.strings + offset).decode() if offset else None


# ------------------------------------------------------------------------------ errors
@dataclass(frozen=True)
class _Problem:
    """What the engine's ssx_md_error says, as Python values."""

    subject: str | None
    text: str | None
    other: str | None
    type: str
    line: int
    count: int
    detail: str


def _optional(pointer: Any) -> str | None:
    return None if pointer == ffi.NULL else ffi.string(pointer).decode()


_MESSAGES: dict[str, Callable[[_Problem], str]] = {
    "SSX_MD_NOT_XML": lambda p: f"not well-formed XML: line {p.line}: {p.detail}",
    "SSX_MD_NO_FMI_ROOT": lambda p: "the root element is not an fmiModelDescription with an "
                                    "fmiVersion",
    "SSX_MD_TYPE_WITHOUT_ELEMENT": lambda p: f"SimpleType {p.subject!r} has no type element",
    "SSX_MD_VARIABLE_WITHOUT_NAME": lambda p: f"a ScalarVariable has no name (valueReference "
                                              f"{p.text!r})",
    "SSX_MD_NO_TYPE_ELEMENT": lambda p: f"variable {p.subject!r} has no type element "
                                        f"({', '.join(_value_types())})",
    "SSX_MD_VALUE_REFERENCE_NOT_INTEGER": lambda p: f"variable {p.subject!r}: valueReference "
                                                    f"{p.text!r} is not an integer",
    "SSX_MD_VALUE_REFERENCE_OUT_OF_RANGE": lambda p: f"variable {p.subject!r}: valueReference "
                                                     f"{(p.text or '').strip()} is outside "
                                                     f"0..{MAX_VALUE_REFERENCE}",
    "SSX_MD_BAD_START": lambda p: f"variable {p.subject!r}: start {p.text!r} is not a {p.type} "
                                  "value",
    "SSX_MD_UNDEFINED_TYPE": lambda p: f"variable {p.subject!r}: declaredType {p.text!r} is not "
                                       "defined",
    "SSX_MD_BAD_COMBINATION": lambda p: f"variable {p.subject!r}: causality={p.text!r} with "
                                        f"variability={p.other!r} is not allowed",
    "SSX_MD_BAD_INITIAL": lambda p: f"variable {p.subject!r}: initial={p.text!r} is not one of "
                                    "exact, approx, calculated",
    "SSX_MD_BAD_INDEX": lambda p: f"ModelStructure index {p.text!r} names no variable (there "
                                  f"are {p.count})",
    "SSX_MD_TOO_LARGE": lambda p: "the file is 4 GiB or larger, too large to read",
    "SSX_MD_NO_MEMORY": lambda p: "out of memory while reading it",
}


def _value_types() -> tuple[str, ...]:
    """The type elements of a ScalarVariable: "Real", ..., "Enumeration" (the engine's words)."""
    engine = lib()
    return words()[engine.SSX_MD_REAL:engine.SSX_MD_ENUMERATION + 1]


def problem_message(md: Any, where: str | Path) -> str | None:
    """Why the engine stopped reading `md` (None: it did not, or at a root element of another
    FMI version, which declared_version tells)."""
    if md.error.problem in (lib().SSX_MD_OK, lib().SSX_MD_NOT_FMI2):
        return None
    return _message(md.error, str(where))


def _message(error: Any, where: str) -> str:
    problem = _Problem(_optional(error.subject), _optional(error.text), _optional(error.other),
                       words()[error.word], int(error.line), int(error.count),
                       ffi.string(error.detail).decode("utf-8", "replace"))
    kind = ffi.string(ffi.cast("ssx_md_problem", error.problem))
    return f"{where}: modelDescription.xml: {_MESSAGES[kind](problem)}"


# ------------------------------------------------------------------------------ the description
def kept_attributes(md: Any) -> dict[str | None, dict[str | None, str | None]]:
    """The attributes the engine kept (root, interfaces, DefaultExperiment), by element."""
    elements: dict[str | None, dict[str | None, str | None]] = {}
    for k in range(md.attribute_count):
        kept = md.attributes[k]
        elements.setdefault(_text(md, kept.element), {})[_text(md, kept.name)] = \
            _text(md, kept.value)
    return elements


def describe(md: Any, where: str | Path) -> ModelDescription:
    """fmpy's objects of what the engine read (md read without a problem)."""
    where = str(where)
    from fmpy.model_description import (
        CoSimulation,
        DefaultExperiment,
        ModelDescription,
        ModelExchange,
        SimpleType,
    )

    def text(offset: int) -> str | None:
        return _text(md, offset)

    elements = kept_attributes(md)
    description = ModelDescription()
    root = elements.get("fmiModelDescription", {})
    for name in _ROOT_TEXT:
        if name in root:
            setattr(description, name, root[name])
    description.numberOfContinuousStates = int(md.derivative_count)
    description.numberOfEventIndicators = _count(root.get("numberOfEventIndicators"), where)
    if "CoSimulation" in elements:
        description.coSimulation = interface_flags(CoSimulation(), elements["CoSimulation"])
    if "ModelExchange" in elements:
        description.modelExchange = interface_flags(ModelExchange(), elements["ModelExchange"])
    if "DefaultExperiment" in elements:
        experiment = elements["DefaultExperiment"]
        description.defaultExperiment = DefaultExperiment(
            startTime=experiment.get("startTime"), stopTime=experiment.get("stopTime"),
            tolerance=experiment.get("tolerance"), stepSize=experiment.get("stepSize"))
    for k in range(md.type_count):
        simple = md.types[k]
        description.typeDefinitions.append(SimpleType(
            name=text(simple.name), type=text(simple.type), description=text(simple.description),
            unit=text(simple.unit), quantity=text(simple.quantity)))
    variables = VariableTable(md, description.typeDefinitions)
    description.modelVariables = variables
    description.outputs = _outputs(md, variables)
    return description


def _count(text: str | None, where: str) -> int:
    """numberOfEventIndicators: absent means none (FMI 2.0's default); at most
    MAX_EVENT_INDICATORS, checked before anything is allocated for them."""
    if text is None:
        return 0
    try:
        count = int(text)
    except ValueError:
        count = -1
    shown = repr(text) if len(text) <= 40 else repr(text[:40]) + "..."
    if count < 0:
        raise FMUFileError(f"{where}: modelDescription.xml: numberOfEventIndicators={shown} is "
                           "not a non-negative integer")
    if count > MAX_EVENT_INDICATORS:
        raise FMUFileError(f"{where}: modelDescription.xml: numberOfEventIndicators={shown} is "
                           f"beyond syssimx's limit of {MAX_EVENT_INDICATORS}")
    return count


def interface_flags(interface: Any, attributes: dict[str | None, str | None]) -> Any:
    from fmpy.model_description import CoSimulation

    interface.modelIdentifier = attributes.get("modelIdentifier")
    cosimulation = isinstance(interface, CoSimulation)
    for name in _INTERFACE_FLAGS + (_COSIMULATION_FLAGS if cosimulation else ()):
        setattr(interface, name, attributes.get(name) in ("true", "1"))
    if cosimulation:
        # lenient like the flags: a value that is no count means no output derivatives
        order = (attributes.get("maxOutputDerivativeOrder") or "0").strip()
        interface.maxOutputDerivativeOrder = int(order) if order.isdigit() else 0
    return interface


def _outputs(md: Any, variables: VariableTable) -> list[Unknown]:
    """ModelStructure/Outputs; a variable named by several Unknowns is made once."""
    from fmpy.model_description import Unknown

    count = int(md.output_count)
    if count == 0:
        return []
    indices = ffi.unpack(md.output, count)
    firsts = ffi.unpack(md.first_dependency, count)
    lengths = ffi.unpack(md.dependency_count, count)
    dependencies = ffi.unpack(md.dependencies, md.dependency_total) if md.dependency_total else []
    # sorted set, not np.unique: that imports numpy.ma on first use, a tenth of a small run
    named = np.array(sorted(set(indices + dependencies)), dtype=np.int64)
    made = dict(zip(named.tolist(), variables.make(named), strict=True))
    outputs = []
    for index, first, length in zip(indices, firsts, lengths, strict=True):
        unknown = Unknown(index=index + 1)
        unknown.variable = made[index]
        if length >= 0:  # without the attribute, it depends on everything
            unknown.dependencies = [made[j] for j in dependencies[first:first + length]]
        outputs.append(unknown)
    return outputs
