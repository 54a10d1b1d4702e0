"""The member FMUs an exported FMU carries, unpacked under resources/members/."""

from __future__ import annotations

import re
import zipfile
from collections.abc import Mapping
from pathlib import PurePosixPath
from typing import Any

from ..components.fmu import FMUComponent
from ..errors import ConfigurationError

MEMBERS = "resources/members"


def member_folders(components: Mapping[str, Any]) -> dict[str, str]:
    """A folder name under resources/members for each member FMU archive (by its path), unique
    and file-name safe."""
    folders: dict[str, str] = {}
    for component in components.values():
        if isinstance(component, FMUComponent) and component.fmu_path not in folders:
            stem = re.sub(r"[^A-Za-z0-9_.-]", "_", component.info.path.stem) or "fmu"
            name, number = stem, 1
            while name in folders.values():
                number += 1
                name = f"{stem}_{number}"
            folders[component.fmu_path] = name
    return folders


def add_members(archive: zipfile.ZipFile, folders: Mapping[str, str]) -> None:
    """Copy every member archive's entries into `archive` under its folder, as they are (the
    member's own binaries, resources and description)."""
    for fmu_path, folder in folders.items():
        with zipfile.ZipFile(fmu_path) as member:
            for entry in member.infolist():
                if entry.is_dir():
                    continue
                parts = PurePosixPath(entry.filename).parts
                if entry.filename.startswith("/") or ".." in parts:
                    raise ConfigurationError(f"{fmu_path}: its entry {entry.filename!r} "
                                             "lies outside the archive")
                target = f"{MEMBERS}/{folder}/{entry.filename}"
                info = zipfile.ZipInfo(target, entry.date_time)
                info.external_attr = entry.external_attr
                info.compress_type = zipfile.ZIP_DEFLATED
                archive.writestr(info, member.read(entry))
