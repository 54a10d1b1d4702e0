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
# The most bytes modelDescription.xml may inflate to: far above any exported model's (a
# million variables take about 250 MB), far below what would exhaust a machine's memory while
# it is read and decoded (a 1 MB archive can inflate to GiBs).
DESCRIPTION_SIZE_LIMIT = 256 * 2**20


class Described(NamedTuple):
    """A modelDescription and the standard it is of."""

    standard: Standard
    description: ModelDescription


def read_description(stream: IO[bytes], where: str | Path,
                     declared_size: int | None = None) -> Described:
    """Read modelDescription.xml from `stream` (of the FMU archive `where`, whose directory
    declares it `declared_size` bytes long, when it is an archive's member); FMUFileError
    naming `where` if it is unusable, larger than DESCRIPTION_SIZE_LIMIT or of an FMI version
    syssimx does not run."""
    text = as_utf8(_bounded_read(stream, where, declared_size), where)
    md = engine_description(text, where)
    version = declared_version(md)
    standard = standard_of(version)
    if standard is None:
        raise FMUFileError(problem_message(md, where) or f"{where}: FMI version {version} is "
                           f"not supported (syssimx runs {supported()})")
    return Described(standard, standard.describe(md, Path(where), text))


def check_declared_size(declared_size: int, where: str | Path) -> None:
    """FMUFileError when the archive `where` declares its description larger than
    DESCRIPTION_SIZE_LIMIT."""
    if declared_size > DESCRIPTION_SIZE_LIMIT:
        raise FMUFileError(f"{where}: modelDescription.xml declares {declared_size} bytes, more "
                           f"than the {DESCRIPTION_SIZE_LIMIT} bytes syssimx reads of a "
                           "description")


def _bounded_read(stream: IO[bytes], where: str | Path,
                  declared_size: int | None) -> bytearray:
    """The whole stream, refused before reading when its declared size is over the limit, and
    while reading once it is (a header may understate what a member inflates to)."""
    if declared_size is not None:
        check_declared_size(declared_size, where)
    limit = DESCRIPTION_SIZE_LIMIT
    text = bytearray()
    while chunk := stream.read(min(_CHUNK, limit + 1 - len(text))):
        text += chunk
        if len(text) > limit:
            raise FMUFileError(f"{where}: modelDescription.xml inflates to more than the "
                               f"{limit} bytes syssimx reads of a description"
                               + (f" (its archive declares {declared_size})"
                                  if declared_size is not None else ""))
    return text
