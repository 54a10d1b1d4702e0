"""What a file uses that syssimx leaves out, and names that name nothing: a warning naming it
(lenient, as the tools that write SSP files are), or an SSPError under strict=True."""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

from .errors import SSPError, SSPWarning

_PACKAGE = str(Path(__file__).resolve().parents[1])


class Unsupported:
    """Warns once per kind of unsupported element and once per ignored name; under `strict`
    each of them is an SSPError instead."""

    def __init__(self, strict: bool = False, error: type[Exception] = SSPError,
                 warning: type[Warning] = SSPWarning) -> None:
        self.strict = strict
        self.error, self.warning = error, warning  # another front-end's kinds (OSP)
        self.seen: set[str] = set()

    def warn(self, kind: str, where: str) -> None:
        """`kind` is not supported; `where`: the file and the element of its first occurrence."""
        if self.strict:
            raise self.error(f"{kind} is not supported (strict): {where}")
        if kind in self.seen:
            return
        self.seen.add(kind)
        warnings.warn(f"{kind} is not supported and is ignored: {where}", self.warning,
                      stacklevel=_callers_level())

    def ignore(self, problem: str, consequence: str) -> None:
        """Something the file names does not exist (`problem` says what and where): left out
        (`consequence` says what is) with a warning, refused under strict."""
        if self.strict:
            raise self.error(f"{problem} (strict)")
        warnings.warn(f"{problem}; {consequence}", self.warning, stacklevel=_callers_level())


def _callers_level() -> int:
    """The stacklevel that attributes a warning to the first caller outside syssimx (the
    user's load or read), however deep in the reader it was found."""
    level, frame = 1, sys._getframe(2)  # level 1: the method that calls warnings.warn
    while frame is not None and frame.f_code.co_filename.startswith(_PACKAGE):
        level += 1
        frame = frame.f_back
    return level + 1
