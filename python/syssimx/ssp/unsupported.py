"""One warning per kind of unsupported SSP element in a file, naming it: never silence."""

from __future__ import annotations

import warnings

from .errors import SSPWarning


class Unsupported:
    """Collects what a file uses that syssimx leaves out; warns once per kind."""

    def __init__(self) -> None:
        self.seen: set[str] = set()

    def warn(self, kind: str, where: str) -> None:
        """`where`: the file and the element of the first occurrence."""
        if kind in self.seen:
            return
        self.seen.add(kind)
        warnings.warn(f"{kind} is not supported and is ignored: {where}", SSPWarning,
                      stacklevel=4)
