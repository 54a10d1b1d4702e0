"""One warning per kind of unsupported SSP element in a file, naming it: never silence."""

from __future__ import annotations

import warnings
from pathlib import Path

from .errors import SSPWarning


class Unsupported:
    """Collects what a file uses that syssimx leaves out; warns once per kind."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.seen: set[str] = set()

    def warn(self, kind: str, detail: str) -> None:
        if kind in self.seen:
            return
        self.seen.add(kind)
        warnings.warn(f"{self.path}: {kind} is not supported and is ignored ({detail})",
                      SSPWarning, stacklevel=4)
