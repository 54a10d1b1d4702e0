"""What several commands share: their error type, finding an FMU, SSP files, defaults."""

from __future__ import annotations

import os
import sys
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from .. import fmus
from ..core.suggest import did_you_mean


class CommandError(Exception):
    """A failure the user can act on: printed as one line, exit code 1."""


def resolve_fmu(name_or_path: str) -> Path:
    path = Path(name_or_path)
    if path.is_file():
        return path
    bundled = fmus.available()
    if path.suffix == "" and name_or_path in bundled:
        return Path(fmus.path(name_or_path))
    raise CommandError(f"no FMU file {name_or_path!r} and no bundled FMU of that name"
                       f"{did_you_mean(name_or_path, bundled)}; 'syssimx fmus' lists the "
                       f"{len(bundled)} bundled FMUs")


def is_ssp(path: str) -> bool:
    """An SSP (.ssp, .ssd) or OSP (.xml, or a folder holding OspSystemStructure.xml) file."""
    from ..system_files import is_system_file

    return is_system_file(path)


def choose(given: float | None, default: Any, fallback: float) -> float:
    if given is not None:
        return float(given)
    return float(default) if default is not None else fallback


@contextmanager
def working_directory_importable() -> Iterator[None]:
    """Component classes ("module:Class") are also found in the working directory, as with
    SysSimX's command line: a console script's sys.path does not have it."""
    saved = list(sys.path)
    sys.path.insert(0, os.getcwd())
    try:
        yield
    finally:
        sys.path[:] = saved


@contextmanager
def warnings_as_lines() -> Iterator[None]:
    """The warnings given inside (reading an SSP or OSP file names what it leaves out), each
    printed as one line on stderr, as the command line prints its errors."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            yield
        finally:
            for warning in caught:
                print(f"syssimx: warning: {warning.message}", file=sys.stderr)
