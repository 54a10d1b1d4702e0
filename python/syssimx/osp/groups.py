"""Variable groups of an OspModelDescription.xml (the file `<modelName>_OspModelDescription.xml`
beside an FMU, or beside the system structure): named groups of variables, possibly nested
(a LinearMechanicalPort holds a Force and a LinearVelocity group)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .errors import OSPError

SUFFIX = "_OspModelDescription.xml"


@dataclass(frozen=True)
class Group:
    name: str
    kind: str  # the element: Generic, LinearMechanicalPort, Force, ...
    variables: tuple[str, ...]
    groups: tuple[Group, ...]


def find_description(model_name: str, fmu: Path, structure: Path) -> Path | None:
    """Where libcosim looks: beside the FMU first, then beside the system structure."""
    for folder in (fmu.parent, structure.parent):
        candidate = folder / f"{model_name}{SUFFIX}"
        if candidate.is_file():
            return candidate
    return None


def read_groups(path: Path) -> dict[str, Group]:
    """The top-level variable groups of the OspModelDescription at `path`, by name."""
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)
    try:
        root = etree.parse(str(path), parser).getroot()
    except (etree.XMLSyntaxError, OSError) as exc:
        raise OSPError(f"{path}: malformed XML: {exc}") from exc
    container = next((e for e in root if _local(e) == "VariableGroups"), None)
    if _local(root) != "OspModelDescription" or container is None:
        raise OSPError(f"{path}: not an OSP model description (no <OspModelDescription> "
                       "with <VariableGroups>)")
    groups = [_group(e, path) for e in container if isinstance(e.tag, str)]
    return {g.name: g for g in groups}


def _group(element: Any, path: Path) -> Group:
    name = element.get("name")
    if name is None:
        raise OSPError(f"{path}: <{_local(element)}> (line {element.sourceline}) has no name")
    variables, groups = [], []
    for child in element:
        if not isinstance(child.tag, str):
            continue
        if _local(child) == "Variable":
            if child.get("ref") is None:
                raise OSPError(f"{path}: <Variable> (line {child.sourceline}) has no ref")
            variables.append(child.get("ref"))
        else:
            groups.append(_group(child, path))
    return Group(name, _local(element), tuple(variables), tuple(groups))


def find_group(groups: dict[str, Group], name: str) -> Group | None:
    """The group `name`: a top-level one, else the first nested one of that name."""
    if name in groups:
        return groups[name]
    pending = [g for group in groups.values() for g in group.groups]
    while pending:
        group = pending.pop(0)
        if group.name == name:
            return group
        pending.extend(group.groups)
    return None


def _local(element: Any) -> str:
    return str(element.tag).rpartition("}")[2] if isinstance(element.tag, str) else ""
