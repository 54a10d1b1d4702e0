"""A plan's text for a build without Python: the records Python's build uses, each FMU's
folder where the caller puts it."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from ..errors import ConfigurationError
from .records import PlanRecords

# the place of the FOLDER field in the records that load an FMU
_FOLDER_FIELD = {"fmu": 3, "model_exchange": 5}


def with_folders(records: PlanRecords, folders: Mapping[str, str | Path]) -> PlanRecords:
    """`records` with the unpacked folder of each FMU component named in `folders` (by
    component name; a relative folder is taken from the base folder of the build)."""
    unknown = set(folders) - {fields[0] for keyword, fields, _ in records.records
                              if keyword in _FOLDER_FIELD}
    if unknown:
        raise ConfigurationError(f"folders: {sorted(unknown)[0]!r} is no FMU component of the "
                                 "plan")
    moved = PlanRecords()
    for keyword, fields, about in records.records:
        field = _FOLDER_FIELD.get(keyword)
        if field is not None and fields[0] in folders:
            fields = (*fields[:field], str(folders[str(fields[0])]), *fields[field + 1:])
        moved.add(keyword, *fields, about=about)
    return moved
