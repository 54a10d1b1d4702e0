"""What syssimx needs from an FMU archive: validated files, ports, parameters, feedthrough.

Everything here is checked before an FMU is loaded, so a broken or foreign .fmu gives a clear
error naming the file and what is wrong with it.
"""

from __future__ import annotations

import logging
import sys
import zipfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from fmpy import read_model_description
from fmpy.model_description import ModelDescription, ModelVariable

from ..core.port import PortSpec, PortType
from ..errors import FMUFileError
from ..graph.analysis import feedthrough_from_model_description
from ..units import to_unit

logger = logging.getLogger("syssimx.fmu")

_PORT_TYPES = {"Real": PortType.REAL, "Integer": PortType.INT, "Enumeration": PortType.INT,
               "Boolean": PortType.BOOL}

PLATFORM = "linux64" if sys.platform.startswith("linux") else sys.platform


@dataclass(frozen=True)
class Parameter:
    """A settable FMU parameter (causality "parameter")."""

    name: str
    value_reference: int
    type: PortType
    unit: str | None
    tunable: bool
    start: float | int | bool | str | None


@dataclass
class FMUInfo:
    """The facts of one FMU archive syssimx uses."""

    path: Path
    description: ModelDescription
    model_identifier: str
    can_get_set_state: bool
    variables: dict[str, ModelVariable]
    input_specs: dict[str, PortSpec] = field(default_factory=dict)
    output_specs: dict[str, PortSpec] = field(default_factory=dict)
    parameters: dict[str, Parameter] = field(default_factory=dict)
    feedthrough: dict[str, set[str]] = field(default_factory=dict)

    def binary_name(self) -> str:
        return f"binaries/{PLATFORM}/{self.model_identifier}.so"


def variable_unit(variable: ModelVariable) -> str | None:
    """The variable's unit, inherited from its declaredType when the variable has none."""
    if variable.unit:
        return variable.unit
    declared = variable.declaredType
    return getattr(declared, "unit", None) or None


def _pint_unit(unit: str | None, where: str) -> str | None:
    """`unit` if pint reads it (else its lower-case spelling, e.g. "Ohm"); a unit pint cannot
    read is dropped with a warning, so the FMU stays usable without unit conversion there."""
    for candidate in (unit, unit.lower() if unit else None):
        if candidate:
            try:
                to_unit(candidate)
                return candidate
            except ValueError:
                continue
    if unit:
        logger.warning("%s: unit %r is unknown to pint; the port carries no unit", where, unit)
    return None


def _start_value(variable: ModelVariable, kind: PortType) -> float | int | bool | str | None:
    start: Any = variable.start
    if start is None:
        return None
    if kind == PortType.REAL:
        return float(start)
    if kind == PortType.INT:
        return int(start)
    if kind == PortType.BOOL:
        return start in (True, "true", "1", 1)
    return str(start)


def _check_archive(path: Path) -> None:
    if not path.is_file():
        raise FMUFileError(f"FMU file not found: {path}")
    if not zipfile.is_zipfile(path):
        raise FMUFileError(f"{path} is not an FMU: the file is not a zip archive")
    with zipfile.ZipFile(path) as archive:
        names = set(archive.namelist())
    if "modelDescription.xml" not in names:
        raise FMUFileError(f"{path} is not an FMU: the archive has no modelDescription.xml")


def read_fmu(fmu_path: str | Path) -> FMUInfo:
    """Validate the archive and read its model description (no extraction, no loading)."""
    path = Path(fmu_path).resolve()
    _check_archive(path)
    try:
        description = read_model_description(str(path), validate=False)
    except Exception as exc:  # fmpy raises many kinds for a malformed description
        raise FMUFileError(f"{path}: unreadable modelDescription.xml: {exc}") from exc
    if description.fmiVersion != "2.0":
        raise FMUFileError(f"{path}: FMI version {description.fmiVersion} is not supported "
                           "(syssimx runs FMI 2.0 Co-Simulation FMUs)")
    if description.coSimulation is None:
        raise FMUFileError(f"{path} is a Model-Exchange-only FMU; syssimx needs Co-Simulation")
    info = FMUInfo(path=path, description=description,
                   model_identifier=description.coSimulation.modelIdentifier,
                   can_get_set_state=bool(description.coSimulation.canGetAndSetFMUstate),
                   variables={v.name: v for v in description.modelVariables})
    with zipfile.ZipFile(path) as archive:
        if info.binary_name() not in archive.namelist():
            raise FMUFileError(f"{path} has no {PLATFORM} binary ({info.binary_name()} missing)")
    _collect_ports_and_parameters(info)
    _collect_feedthrough(info)
    return info


def _collect_ports_and_parameters(info: FMUInfo) -> None:
    for variable in info.description.modelVariables:
        kind = _PORT_TYPES.get(variable.type)
        if kind is None:
            continue  # String variables have no place among the engine's doubles
        unit = (_pint_unit(variable_unit(variable), f"{info.path.name}: {variable.name}")
                if kind == PortType.REAL else None)
        if variable.causality in ("input", "output"):
            spec = PortSpec(variable.name, kind, "in" if variable.causality == "input" else "out",
                            unit, variable.description)
            specs = info.input_specs if spec.direction == "in" else info.output_specs
            specs[variable.name] = spec
        elif variable.causality == "parameter":
            info.parameters[variable.name] = Parameter(
                variable.name, variable.valueReference, kind, unit,
                variable.variability == "tunable", _start_value(variable, kind))


def _collect_feedthrough(info: FMUInfo) -> None:
    """Output -> the inputs it depends on directly, from ModelStructure."""
    declared = feedthrough_from_model_description(info.description)
    info.feedthrough = {name: declared[name] & set(info.input_specs)
                        for name in info.output_specs}


def start_value(info: FMUInfo, name: str) -> float | int | bool | str | None:
    variable = info.variables[name]
    return _start_value(variable, _PORT_TYPES.get(variable.type, PortType.STRING))
