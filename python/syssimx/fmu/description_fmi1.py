"""FMI 1.0 modelDescription.xml, read by the engine's reader into fmpy's objects.

The engine reads FMI 1.0's variables in FMI 2.0's words (see finish_variable in the reader: a
parameter is a fixed parameter, internal is local, a negated alias is no port). What differs
around them is here: one model identifier on the root for both interfaces; an
`Implementation` element (CoSimulation_StandAlone or CoSimulation_Tool) makes the FMU a
Co-Simulation one, its absence a Model Exchange one (an FMI 1.0 FMU has one interface);
`numberOfContinuousStates` on the root; no FMU state (FMI 1.0 has no get/set FMU state), no
directional derivatives and no ModelStructure (every output depends on every input).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import FMUFileError
from .description_fmi2 import describe, interface_flags, kept_attributes

if TYPE_CHECKING:
    from fmpy.model_description import ModelDescription

MAX_CONTINUOUS_STATES = 1_000_000  # as many as event indicators (description_fmi2.py)

def describe_fmi1(md: Any, path: Path) -> ModelDescription:
    """The description of an FMI 1.0 modelDescription the engine read without a problem."""
    from fmpy.model_description import CoSimulation, ModelExchange

    description = describe(md, path)
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
