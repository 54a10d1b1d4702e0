"""Extracted FMU archives, shared by the components made from the same file.

FMI 2.0 lets one loaded binary serve many instances unless the FMU declares
canBeInstantiatedOnlyOncePerProcess. Sharing one extraction means the dynamic loader maps the
binary once: 100 components of one FMU then step through one copy of its code instead of 100
(measured: 2.3x faster for 100 pendulums). An FMU that may be instantiated only once per process
gets a private extraction each time, so each instance has its own copy of the binary's globals.
Every extraction folder is removed by its last user, on a failed extraction, at exit, and on
SIGTERM and SIGHUP (where nobody else handles them). Beside each folder `syssimx_X` lies
`syssimx_X.owner`, the owning process's id and start time: the first extraction of a process
removes the folders whose owner is gone (killed by SIGKILL, or by a signal someone else
handled), and those left without an owner file for a day by versions before it. A forked
child (an ensemble's worker) inherits its parent's folders without owning them: it never
removes them, and extracts its own.
"""

from __future__ import annotations

import atexit
import os
import shutil
import signal
import socket
import tempfile
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .archive import extract

PREFIX = "syssimx_"
OWNER_SUFFIX = ".owner"
ORPHAN_AGE = 24 * 3600.0  # seconds: a folder without an owner file is that old when stale


@dataclass
class _Extraction:
    directory: Path
    users: int
    shared_value: Any = None  # see ExtractionCache.shared


class ExtractionCache:
    """Reference-counted extraction directories, keyed by archive identity."""

    def __init__(self) -> None:
        # reentrant: a component collected while acquire holds the lock releases through it
        self._lock = threading.RLock()
        self._entries: dict[tuple[str, int, int], _Extraction] = {}
        self._directories: set[Path] = set()  # every folder not yet removed, private ones too
        # folder -> member -> its resolved path, checked once per extraction
        self._binaries: dict[Path, dict[str, Path]] = {}
        self._swept = False
        self._inherited: set[Path] = set()  # a forked child's parent's folders: not ours
        atexit.register(self.remove_all)
        os.register_at_fork(after_in_child=self._forget_parents_folders)

    def _forget_parents_folders(self) -> None:
        self._inherited |= self._directories
        self._directories = set()
        self._entries = {}
        self._lock = threading.RLock()  # another thread of the parent may have held it

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

    def shared(self, key: tuple[str, int, int], make: Callable[[], Any]) -> Any:
        """What `make` returns, made once per shared extraction and kept as long as it is (the
        pool the engine makes the bindings of its FMUs in)."""
        with self._lock:
            entry = self._entries[key]
            if entry.shared_value is None:
                entry.shared_value = make()
            return entry.shared_value

    def release(self, directory: Path, key: tuple[str, int, int] | None) -> None:
        """Give back what acquire returned; the last user removes the directory."""
        if directory in self._inherited:
            return  # a forked child's copy of its parent's component: the parent removes it
        if key is not None:
            with self._lock:
                entry = self._entries[key]
                entry.users -= 1
                if entry.users > 0:
                    return
                del self._entries[key]
        self._directories.discard(directory)
        self._binaries.pop(directory, None)
        _remove(directory)

    def _extract(self, archive: Path) -> Path:
        if not self._swept:
            self._swept = True
            remove_stale_folders(Path(tempfile.gettempdir()))
            _remove_on_signals(self)
        directory = Path(tempfile.mkdtemp(prefix=PREFIX))
        try:
            _owner_file(directory).write_text(_owner_line())
            extract(archive, directory)  # removes the folder if it fails
        except BaseException:
            _remove(directory)
            raise
        self._directories.add(directory)
        self._inherited.discard(directory)  # the parent's removed folder's name, reused
        return directory

    def remove_all(self) -> None:
        """Remove every extraction folder (at exit: the binaries are no longer needed)."""
        for directory in list(self._directories):
            _remove(directory)
        self._directories.clear()


def _owner_file(directory: Path) -> Path:
    return directory.with_name(directory.name + OWNER_SUFFIX)


def _remove(directory: Path) -> None:
    shutil.rmtree(directory, ignore_errors=True)
    _owner_file(directory).unlink(missing_ok=True)


def _process_stat(pid: int) -> list[str]:
    """The fields of /proc/<pid>/stat after the command's name ([] when unknown): [0] is the
    state, [19] the start time in clock ticks since boot."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except (OSError, IndexError):
        return []


def _start_time(pid: int) -> str:
    """The process's start time ("" when unknown): with its id, it tells the owner from a later
    process that got the same id."""
    fields = _process_stat(pid)
    return fields[19] if len(fields) > 19 else ""


def _here() -> str:
    """This machine and PID namespace: a process id means something only there (a container
    sharing the temporary folder counts its processes apart)."""
    try:
        namespace = os.readlink("/proc/self/ns/pid")
    except OSError:
        namespace = "?"
    return f"{socket.gethostname()}/{namespace}".replace(" ", "_")


def _owner_line() -> str:
    return f"{os.getpid()} {_start_time(os.getpid()) or '?'} {_here()}\n"


def _owner_alive(owner: Path) -> bool:
    try:
        pid_text, *rest = owner.read_text().split()
        pid = int(pid_text)
    except (OSError, ValueError):
        return True  # being written, or not ours to judge
    started = [rest[0]] if rest and rest[0] != "?" else []
    if len(rest) > 1 and rest[1] != _here():
        return True  # another machine's or container's process: not ours to judge
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True  # another user's process: alive
    fields = _process_stat(pid)
    if fields and fields[0] in ("Z", "X"):
        return False  # ended, not yet reaped by its parent
    now_started = fields[19] if len(fields) > 19 else ""
    return not started or now_started in ("", started[0])


def remove_stale_folders(temporary: Path) -> list[Path]:
    """Remove the extraction folders in `temporary` whose owning process is gone, and those
    without an owner file older than ORPHAN_AGE; returns the folders removed."""
    removed = []
    try:
        candidates = [p for p in temporary.iterdir() if p.name.startswith(PREFIX)]
    except OSError:
        return removed
    now = time.time()
    for path in candidates:
        try:
            if path.name.endswith(OWNER_SUFFIX):
                folder = path.with_name(path.name[:-len(OWNER_SUFFIX)])
                stale = path.stat().st_uid == os.getuid() and not _owner_alive(path)
            else:
                folder = path
                stale = (path.is_dir() and not _owner_file(path).exists()
                         and path.stat().st_uid == os.getuid()
                         and now - path.stat().st_mtime > ORPHAN_AGE)
        except OSError:
            continue
        if stale:
            _remove(folder)
            removed.append(folder)
    return removed


def remove_extractions_on_signals() -> None:
    """Remove this process's extraction folders on SIGTERM and SIGHUP, where they still have
    their default action; called on the main thread (elsewhere it does nothing). A process's
    first extraction calls it; a process whose FMUs are extracted on other threads (a sweep's
    worker) calls it on its main thread."""
    _remove_on_signals(extractions)


def _remove_on_signals(cache: ExtractionCache) -> None:
    """SIGTERM and SIGHUP end the process without atexit: where they still have their default
    action, remove the folders first, then end by the same signal."""
    def remove_then_end(signum: int, _frame: Any) -> None:
        cache.remove_all()
        signal.signal(signum, signal.SIG_DFL)
        os.kill(os.getpid(), signum)

    if threading.current_thread() is not threading.main_thread():
        return  # signal handlers are the main thread's to set
    for signum in (signal.SIGTERM, signal.SIGHUP):
        if signal.getsignal(signum) == signal.SIG_DFL:
            signal.signal(signum, remove_then_end)


extractions = ExtractionCache()
