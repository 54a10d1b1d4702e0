"""What a file uses that syssimx leaves out, and names that name nothing: a warning naming it
(lenient, as the tools that write SSP files are), or an SSPError under strict=True."""

from __future__ import annotations

import warnings

from .errors import SSPError, SSPWarning


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
                      stacklevel=4)

    def ignore(self, problem: str, consequence: str) -> None:
        """Something the file names does not exist (`problem` says what and where): left out
        (`consequence` says what is) with a warning, refused under strict."""
        if self.strict:
            raise self.error(f"{problem} (strict)")
        warnings.warn(f"{problem}; {consequence}", self.warning, stacklevel=4)
