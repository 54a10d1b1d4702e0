"""modelDescription.xml, read once: the one place the FMI version is decided.

The engine's reader (description_fmi2.py) reads the text, in UTF-8 whatever encoding the file
declares (encoding.py); it stops at the root element of a
version it does not read, and tells the fmiVersion either way. That version picks the FMU's
standard (standards.py), which makes the description.
"""

from __future__ import annotations

from pathlib import Path
from typing import IO, TYPE_CHECKING, NamedTuple

from ..errors import FMUFileError
from .description_fmi2 import declared_version, engine_description, problem_message
from .encoding import as_utf8
from .standards import Standard, standard_of, supported

if TYPE_CHECKING:
    from fmpy.model_description import ModelDescription

_CHUNK = 2**20


class Described(NamedTuple):
    """A modelDescription and the standard it is of."""

    standard: Standard
    description: ModelDescription


def read_description(stream: IO[bytes], where: str | Path) -> Described:
    """Read modelDescription.xml from `stream` (of the FMU archive `where`); FMUFileError
    naming `where` if it is unusable or of an FMI version syssimx does not run."""
    text = bytearray()
    while chunk := stream.read(_CHUNK):
        text += chunk
    md = engine_description(as_utf8(text, where), where)
    del text  # the engine copied what it keeps
    version = declared_version(md)
    standard = standard_of(version)
    if standard is None:
        raise FMUFileError(problem_message(md, where) or f"{where}: FMI version {version} is "
                           f"not supported (syssimx runs {supported()})")
    return Described(standard, standard.describe(md, Path(where)))
