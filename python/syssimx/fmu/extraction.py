"""Extracted FMU archives, shared by the components made from the same file.

FMI 2.0 lets one loaded binary serve many instances unless the FMU declares
canBeInstantiatedOnlyOncePerProcess. Sharing one extraction means the dynamic loader maps the
binary once: 100 components of one FMU then step through one copy of its code instead of 100
(measured: 2.3x faster for 100 pendulums). An FMU that may be instantiated only once per process
gets a private extraction each time, so each instance has its own copy of the binary's globals.
Every extraction folder is removed by its last user, on a failed extraction, and at exit.
"""

from __future__ import annotations

import atexit
import shutil
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path

from .archive import extract


@dataclass
class _Extraction:
    directory: Path
    users: int


class ExtractionCache:
    """Reference-counted extraction directories, keyed by archive identity."""

    def __init__(self) -> None:
        # reentrant: a component collected while acquire holds the lock releases through it
        self._lock = threading.RLock()
        self._entries: dict[tuple[str, int, int], _Extraction] = {}
        self._directories: set[Path] = set()  # every folder not yet removed, private ones too
        # folder -> member -> its resolved path, checked once per extraction
        self._binaries: dict[Path, dict[str, Path]] = {}
        atexit.register(self.remove_all)

    def acquire(self, archive: Path, shareable: bool) -> tuple[Path, tuple[str, int, int] | None]:
        """The directory holding `archive` (a resolved path) extracted, and the key to release
        it with (None for a private extraction, which the caller removes itself)."""
        if not shareable:
            return self._extract(archive), None
        stat = archive.stat()
        key = (str(archive), stat.st_mtime_ns, stat.st_size)
        with self._lock:
            entry = self._entries.get(key)
            if entry is None:
                entry = self._entries[key] = _Extraction(self._extract(archive), 0)
            entry.users += 1
            return entry.directory, key

    def binary(self, directory: Path, member: str) -> Path | None:
        """The extracted file `member` of `directory` resolved, or None unless it is a file
        inside the folder (a link cannot lead out of it)."""
        with self._lock:
            checked = self._binaries.setdefault(directory, {})
            if member not in checked:
                path = (directory / member).resolve()
                if not (path.is_relative_to(directory.resolve()) and path.is_file()):
                    return None
                checked[member] = path
            return checked[member]

    def release(self, directory: Path, key: tuple[str, int, int] | None) -> None:
        """Give back what acquire returned; the last user removes the directory."""
        if key is not None:
            with self._lock:
                entry = self._entries[key]
                entry.users -= 1
                if entry.users > 0:
                    return
                del self._entries[key]
        self._directories.discard(directory)
        self._binaries.pop(directory, None)
        shutil.rmtree(directory, ignore_errors=True)

    def _extract(self, archive: Path) -> Path:
        directory = Path(tempfile.mkdtemp(prefix="syssimx_"))
        extract(archive, directory)  # removes the folder if it fails
        self._directories.add(directory)
        return directory

    def remove_all(self) -> None:
        """Remove every extraction folder (at exit: the binaries are no longer needed)."""
        for directory in list(self._directories):
            shutil.rmtree(directory, ignore_errors=True)
        self._directories.clear()


extractions = ExtractionCache()
