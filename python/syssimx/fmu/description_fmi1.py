"""FMI 1.0 modelDescription.xml, read by the engine's reader into fmpy's objects.

The engine reads FMI 1.0's variables in FMI 2.0's words (see finish_variable in the reader: a
parameter is a fixed parameter, internal is local, a negated alias is no port). What differs
around them is here: one model identifier on the root for both interfaces; an
`Implementation` element (CoSimulation_StandAlone or CoSimulation_Tool) makes the FMU a
Co-Simulation one, its absence a Model Exchange one (an FMI 1.0 FMU has one interface);
`numberOfContinuousStates` on the root; no FMU state (FMI 1.0 has no get/set FMU state), no
directional derivatives and no ModelStructure: an output's direct dependencies are its own
`DirectDependency` element, read here into FMI 2.0's ModelStructure outputs (without the
element, the output depends on every input).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import FMUFileError
from .description_fmi2 import describe, interface_flags, kept_attributes

if TYPE_CHECKING:
    from fmpy.model_description import ModelDescription, Unknown

    from .variable_table import VariableTable

MAX_CONTINUOUS_STATES = 1_000_000  # as many as event indicators (description_fmi2.py)

def describe_fmi1(md: Any, path: Path, text: bytes | bytearray) -> ModelDescription:
    """The description of an FMI 1.0 modelDescription (`text`, in UTF-8) the engine read
    without a problem."""
    from fmpy.model_description import CoSimulation, ModelExchange

    description = describe(md, path)
    # the engine's reader keeps no element text: the Names are read here, and only from the
    # descriptions that have any
    if b"<DirectDependency" in text:
        description.outputs = _direct_dependencies(text, description.modelVariables)
    elements = kept_attributes(md)
    root = elements.get("fmiModelDescription", {})
    description.numberOfContinuousStates = _count(root, "numberOfContinuousStates", path)
    # Implementation/CoSimulation_*/Capabilities, which the schema requires of Co-Simulation
    capabilities = elements.get("Capabilities")
    identifier = {"modelIdentifier": root.get("modelIdentifier")}
    if capabilities is not None:
        description.coSimulation = interface_flags(CoSimulation(), {**capabilities, **identifier})
    else:
        description.modelExchange = interface_flags(ModelExchange(), identifier)
    return description


def _count(root: dict[str | None, str | None], name: str, path: Path) -> int:
    """A count on the root: absent means none; at most MAX_CONTINUOUS_STATES, checked before
    anything is allocated for them (the engine counts states in a C int)."""
    text = root.get(name)
    try:
        count = int(text) if text is not None else 0
    except ValueError:
        count = -1
    if count < 0:
        raise FMUFileError(f"{path}: modelDescription.xml: {name}={text!r} is not a "
                           "non-negative integer")
    if count > MAX_CONTINUOUS_STATES:
        raise FMUFileError(f"{path}: modelDescription.xml: {name}={text!r} is beyond "
                           f"syssimx's limit of {MAX_CONTINUOUS_STATES}")
    return count


def _direct_dependencies(text: bytes | bytearray, variables: VariableTable) -> list[Unknown]:
    """The outputs with a DirectDependency element, as ModelStructure outputs depending on the
    variables it names (none when it is empty). An output whose element names no variable of
    the FMU, or a description lxml does not parse, is left out: it depends on every input."""
    from fmpy.model_description import Unknown
    from lxml import etree

    # the text is UTF-8 whatever its declaration says (encoding.py made it so)
    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False,
                             encoding="utf-8")
    try:
        root = etree.fromstring(bytes(text), parser)
    except etree.XMLSyntaxError:
        return []
    outputs = []
    for element in root.iterfind("ModelVariables/ScalarVariable[@causality='output']"):
        direct = element.find("DirectDependency")
        index = variables.find(element.get("name", ""))
        if direct is None or index < 0:
            continue
        named = [variables.find((name.text or "").strip()) for name in direct.iterfind("Name")]
        if any(position < 0 for position in named):
            continue
        unknown = Unknown(index=index + 1)
        unknown.variable = variables[index]
        unknown.dependencies = [variables[position] for position in named]
        outputs.append(unknown)
    return outputs
