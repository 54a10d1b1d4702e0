"""The exported FMU's modelDescription.xml (FMI 2.0 or 3.0), generated from its variables."""

from __future__ import annotations

import datetime
import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from .._version import __version__
from .selection import ExportedVariable


@dataclass(frozen=True)
class Description:
    """What the modelDescription says besides the variables."""

    fmi_version: str  # "2.0" or "3.0"
    model_name: str
    model_identifier: str
    token: str  # FMI 2.0 guid, FMI 3.0 instantiationToken
    can_get_set_state: bool
    can_serialize_state: bool
    start_time: float | None = None
    stop_time: float | None = None
    step_size: float | None = None


def model_description(description: Description, variables: Sequence[ExportedVariable],
                      units: Mapping[str, Mapping[str, str]]) -> bytes:
    """The XML document; `units` holds the BaseUnit attributes of the members' units by
    name (a unit no member defines is declared by its name alone)."""
    fmi3 = description.fmi_version == "3.0"
    root = ET.Element("fmiModelDescription", {
        "fmiVersion": description.fmi_version,
        "modelName": description.model_name,
        "instantiationToken" if fmi3 else "guid": description.token,
        "description": "a syssimx system exported as one Co-Simulation FMU",
        "generationTool": f"syssimx {__version__}",
        "generationDateAndTime": datetime.datetime.now(datetime.UTC)
        .strftime("%Y-%m-%dT%H:%M:%SZ"),
        "variableNamingConvention": "flat",
    })
    if not fmi3:
        root.set("numberOfEventIndicators", "0")
    state = {"canGetAndSetFMUState" if fmi3 else "canGetAndSetFMUstate":
             _flag(description.can_get_set_state),
             "canSerializeFMUState" if fmi3 else "canSerializeFMUstate":
             _flag(description.can_serialize_state)}
    co_simulation = {"modelIdentifier": description.model_identifier,
                     "canHandleVariableCommunicationStepSize": "true", **state}
    if fmi3:
        co_simulation.update(hasEventMode="true", mightReturnEarlyFromDoStep="true")
    else:
        co_simulation["canNotUseMemoryManagementFunctions"] = "true"
    ET.SubElement(root, "CoSimulation", co_simulation)
    used = sorted({v.unit for v in variables if v.unit and v.value_type == "real"})
    if used:
        definitions = ET.SubElement(root, "UnitDefinitions")
        for name in used:
            unit = ET.SubElement(definitions, "Unit", name=name)
            if name in units:
                ET.SubElement(unit, "BaseUnit", dict(units[name]))
    experiment = {key: repr(float(value)) for key, value in
                  (("startTime", description.start_time), ("stopTime", description.stop_time),
                   ("stepSize", description.step_size)) if value is not None}
    if experiment:
        ET.SubElement(root, "DefaultExperiment", experiment)
    model_variables = ET.SubElement(root, "ModelVariables")
    if fmi3:
        ET.SubElement(model_variables, "Float64", name="time", valueReference="0",
                      causality="independent", variability="continuous",
                      description="simulation time")
    for variable in variables:
        (_fmi3_variable if fmi3 else _fmi2_variable)(model_variables, variable)
    _model_structure(root, variables, fmi3)
    ET.indent(root)
    return ET.tostring(root, encoding="UTF-8", xml_declaration=True) + b"\n"


def _flag(value: bool) -> str:
    return "true" if value else "false"


def _causality(variable: ExportedVariable) -> dict[str, str]:
    """causality, variability and initial of the variable, by its role."""
    if variable.role == "parameter":
        # set before initialization only: the members are initialized with it
        return {"causality": "parameter", "variability": "fixed", "initial": "exact"}
    # only a Real (Float64) varies continuously in either standard
    continuous = variable.value_type == "real"
    if variable.role == "input":
        return {"causality": "input",
                "variability": "continuous" if continuous else "discrete"}
    variability = "continuous" if variable.role == "output" and continuous else "discrete"
    return {"causality": "output", "variability": variability, "initial": "calculated"}


def _common(variable: ExportedVariable) -> dict[str, str]:
    attributes = {"name": variable.name, "valueReference": str(variable.value_reference),
                  **_causality(variable)}
    if variable.description:
        attributes["description"] = variable.description
    return attributes


FMI2_ELEMENTS = {"real": "Real", "integer": "Integer", "boolean": "Boolean"}
FMI3_ELEMENTS = {"real": "Float64", "integer": "Int32", "boolean": "Boolean"}


def _typed(variable: ExportedVariable) -> dict[str, str]:
    """unit (a Real's only) and start, written as the variable's type writes it."""
    typed: dict[str, str] = {}
    if variable.unit and variable.value_type == "real":
        typed["unit"] = variable.unit
    if variable.start is not None:
        start = float(variable.start)
        typed["start"] = {"real": repr(start), "integer": str(int(start)),
                          "boolean": _flag(start != 0.0)}[variable.value_type]
    return typed


def _fmi2_variable(parent: ET.Element, variable: ExportedVariable) -> None:
    element = ET.SubElement(parent, "ScalarVariable", _common(variable))
    ET.SubElement(element, FMI2_ELEMENTS[variable.value_type], _typed(variable))


def _fmi3_variable(parent: ET.Element, variable: ExportedVariable) -> None:
    ET.SubElement(parent, FMI3_ELEMENTS[variable.value_type],
                  {**_common(variable), **_typed(variable)})


def _model_structure(root: ET.Element, variables: Sequence[ExportedVariable],
                     fmi3: bool) -> None:
    """Outputs and initial unknowns: each output, depending on what the standard assumes when
    nothing is declared (every input)."""
    structure = ET.SubElement(root, "ModelStructure")
    outputs = [v for v in variables if v.role in ("output", "events", "last_event_time")]
    if fmi3:
        for variable in outputs:
            ET.SubElement(structure, "Output", valueReference=str(variable.value_reference))
        for variable in outputs:
            ET.SubElement(structure, "InitialUnknown",
                          valueReference=str(variable.value_reference))
        return
    # FMI 2.0 refers to variables by their 1-based position in ModelVariables
    position = {v.name: i for i, v in enumerate(variables, start=1)}
    listed = ET.SubElement(structure, "Outputs")
    for variable in outputs:
        ET.SubElement(listed, "Unknown", index=str(position[variable.name]))
    initial = ET.SubElement(structure, "InitialUnknowns")
    for variable in outputs:
        ET.SubElement(initial, "Unknown", index=str(position[variable.name]))
