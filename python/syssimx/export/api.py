"""System.export_fmu: the system as one Co-Simulation FMU whose binary is the engine."""

from __future__ import annotations

import hashlib
import re
import uuid
import zipfile
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from .. import _paths
from ..atomic_file import atomic_path
from ..components.fmu import FMUComponent
from ..errors import ConfigurationError
from .export_map import export_map
from .members import add_members, member_folders
from .model_description import Description, model_description
from .refusals import refuse_python
from .selection import ExportedVariable, select

PLATFORM_FOLDERS = {"2.0": "binaries/linux64", "3.0": "binaries/x86_64-linux"}


def export_fmu(system: Any, path: str | Path, fmi_version: str = "2.0",
               inputs: Sequence[str] | None = None, outputs: Sequence[str] | None = None,
               parameters: Sequence[str] = (), *, step_size: float | None = None,
               start_time: float | None = None, stop_time: float | None = None) -> Path:
    """Write `system` as the Co-Simulation FMU `path` (FMI 2.0 or 3.0); returns the path.

    inputs, outputs, parameters: "Component.port" names (default: every Real member input no
    connection drives, every Real member output, no parameter). step_size: the system's
    communication step inside each doStep (None: the importer's step). start_time, stop_time
    and step_size also make the default experiment. A system that runs Python anywhere is
    refused, naming each part."""
    if fmi_version not in PLATFORM_FOLDERS:
        raise ConfigurationError(f"{system.name}: fmi_version is '2.0' or '3.0', not "
                                 f"{fmi_version!r}")
    if step_size is not None and not step_size > 0.0:
        raise ConfigurationError(f"{system.name}: step_size must be positive, got {step_size}")
    folders = member_folders(system.components)
    members = [c for c in system.components.values() if isinstance(c, FMUComponent)]
    # compiled as the system's own run compiles it (what that refuses is refused first)
    plan = system.to_plan(folders={c.name: folders[c.fmu_path] for c in members})
    refuse_python(system)
    isolated = [c.name for c in members if c.isolated]
    if isolated:
        raise ConfigurationError(
            f"{system.name}: cannot export the isolated components {isolated}: the FMU "
            "carries no host process to run their binaries in (leave isolated off)")
    variables = select(system, inputs, outputs, list(parameters))
    _refuse_restarted_parameters(system, variables)
    path = Path(path)
    identifier = _model_identifier(path)
    digest = hashlib.sha256((plan + repr(variables)).encode()).hexdigest()
    token = "{" + str(uuid.uuid5(uuid.NAMESPACE_URL, f"syssimx-export:{digest}")) + "}"
    description = Description(
        fmi_version, system.name, identifier, token,
        can_get_set_state=all(c.can_get_set_state for c in members),
        can_serialize_state=all(c.can_get_set_state and _can_serialize(c) for c in members),
        start_time=start_time, stop_time=stop_time, step_size=step_size)
    document = model_description(description, variables, _member_units(members))
    with atomic_path(path) as written, zipfile.ZipFile(written, "w",
                                                       zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("modelDescription.xml", document)
        archive.write(_paths.export_binary(),
                      f"{PLATFORM_FOLDERS[fmi_version]}/{identifier}.so")
        archive.writestr("resources/system.plan", plan)
        archive.writestr("resources/export.map", export_map(token, step_size, variables))
        add_members(archive, folders)
    return path


def _model_identifier(path: Path) -> str:
    """The FMU's file name as a C identifier: it names the binary."""
    identifier = re.sub(r"\W", "_", path.stem, flags=re.ASCII)
    return identifier if identifier and not identifier[0].isdigit() else f"_{identifier}"


def _can_serialize(component: FMUComponent) -> bool:
    interface = component.info.description.modelExchange if component.model_exchange \
        else component.info.description.coSimulation
    return bool(getattr(interface, "canSerializeFMUstate", False))


def _member_units(members: Sequence[FMUComponent]) -> Mapping[str, Mapping[str, str]]:
    """The BaseUnit attributes of the units the members' modelDescriptions define, by unit
    name (the first member's definition wins)."""
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)
    units: dict[str, Mapping[str, str]] = {}
    for path in dict.fromkeys(component.info.path for component in members):
        with zipfile.ZipFile(path) as archive:
            root = etree.fromstring(archive.read("modelDescription.xml"), parser)
        for unit in root.iterfind("UnitDefinitions/Unit"):
            base = unit.find("BaseUnit")
            if base is not None:
                units.setdefault(unit.get("name", ""), dict(base.attrib))
    return units


def _refuse_restarted_parameters(system: Any, variables: Sequence[ExportedVariable]) -> None:
    """A member the engine restarts at its events starts again from the values of the export:
    a parameter of it set in the exported FMU would apply until its first event only."""
    names = list(system.components)
    restarted = [v.name for v in variables if v.role == "parameter"
                 and system.components[names[v.component]]._engine_restart() is not None]
    if restarted:
        raise ConfigurationError(
            f"{system.name}: cannot export the parameters {restarted}: their component "
            "restarts at its events from the start values it was exported with")

