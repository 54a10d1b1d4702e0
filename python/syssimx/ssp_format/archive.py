"""An .ssp archive unpacked into a temporary folder, or an .ssd file beside its FMUs.

Extraction uses the FMU archive checks: an entry with an absolute path, '..' or a symbolic
link, a corrupt member or content above the size limit is refused before anything lands
outside the temporary folder, and the folder is removed on failure.
"""

from __future__ import annotations

import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

from ..errors import FMUFileError
from ..fmu.archive import extract
from .errors import SSPError

SSD_NAME = "SystemStructure.ssd"


@dataclass(frozen=True)
class Package:
    """Where the system structure is and the folder its relative references start from;
    `temporary` is the extraction folder to remove when the system is dropped (None for .ssd)."""

    ssd: Path
    base: Path
    temporary: Path | None
    origin: Path  # the file the user gave

    def shown(self, path: Path) -> str:
        """How an error names a file: inside an archive as archive:member."""
        if self.temporary is None:
            return str(path)
        return f"{self.origin}:{path.relative_to(self.temporary).as_posix()}"


def open_package(path: str | Path) -> Package:
    """The .ssd of an .ssp archive (extracted) or of a plain .ssd file."""
    path = Path(path)
    if not path.is_file():
        raise SSPError(f"{path}: file not found")
    if path.suffix.lower() != ".ssp":
        return Package(path, path.parent, None, path)
    folder = Path(tempfile.mkdtemp(prefix="syssimx-ssp-"))
    try:
        extract(path, folder)
    except FMUFileError as exc:
        shutil.rmtree(folder, ignore_errors=True)
        raise SSPError(str(exc).replace("is not an FMU", "is not an SSP")) from exc
    ssd = folder / SSD_NAME
    if not ssd.is_file():
        shutil.rmtree(folder, ignore_errors=True)
        raise SSPError(f"{path}: the archive has no {SSD_NAME} at its root")
    return Package(ssd, folder, folder, path)


def resolve(package: Package, reference: str, where: str) -> Path:
    """The file a relative reference (an FMU, .ssv or .ssm `source`) names, inside the
    package's folder; `where` names the referring element for the error."""
    where = f"{package.shown(package.ssd)}: {where}"
    if ":" in reference.split("/")[0]:
        raise SSPError(f"{where}: source {reference!r} is not a relative "
                       "reference (the only kind syssimx reads)")
    target = (package.base / reference).resolve()
    if package.temporary is not None and not target.is_relative_to(package.base.resolve()):
        raise SSPError(f"{where}: source {reference!r} lies outside the archive")
    if reference.startswith(("/", "\\")):
        raise SSPError(f"{where}: source {reference!r} is an absolute path; syssimx reads "
                       "references relative to the system structure's folder only")
    try:
        found = target.is_file()
    except OSError as exc:  # a name too long for the file system, ...
        raise SSPError(f"{where}: source {reference!r} cannot be read: {exc.strerror}") from exc
    if not found:
        raise SSPError(f"{where}: source {reference!r} not found"
                       + (" in the archive" if package.temporary is not None else ""))
    return target
