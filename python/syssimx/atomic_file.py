"""Output files appear whole or not at all.

Every file syssimx writes for a user (CSV, NetCDF, Parquet, SSP archives, plots, graphs) is
written to a temporary name in the target's folder and renamed onto the target once complete:
a rename within one file system is atomic, so a reader, a SIGTERM or a full disk never leaves a
truncated file under the target's name. What an interrupted write leaves is a hidden
``.<name>.<random>.partial<suffix>`` beside it, removed when the write fails in Python.

A target that is a symbolic link is written through it: the file it points to is replaced
(in that file's folder), the link stays. A target that exists and is not a regular file (a
device such as /dev/null, a FIFO, a socket) is written directly, never replaced: renaming a
file over it would destroy it, and its reader would get nothing.
"""

from __future__ import annotations

import os
import secrets
import stat
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path


def resolved_target(target: str | Path) -> Path:
    """The file a write to `target` ends in: the target itself, or what its symbolic links
    lead to (possibly a file that does not exist yet)."""
    target = Path(target)
    return Path(os.path.realpath(target)) if target.is_symlink() else target


def is_special(target: str | Path) -> bool:
    """Whether `target` (after its links) exists and is not a regular file: written directly."""
    try:
        mode = os.stat(target).st_mode
    except OSError:  # absent (or a dangling link): a new regular file
        return False
    return not stat.S_ISREG(mode) and not stat.S_ISDIR(mode)


@contextmanager
def atomic_path(target: str | Path) -> Iterator[Path]:
    """A path to write `target`'s content to: a fresh temporary path beside the file (same
    suffix, so writers that choose a format by it still do), renamed onto it when the block ends
    normally and removed when it raises; for a device or FIFO, the target itself."""
    if is_special(target):  # through its links: /dev/stdout leads to a pipe, not a path
        yield Path(target)
        return
    final = resolved_target(target)
    temporary = final.with_name(f".{final.stem}.{secrets.token_hex(4)}.partial{final.suffix}")
    # created here, honouring the umask, so the file ends with the mode a direct write gives
    os.close(os.open(temporary, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o666))
    try:
        yield temporary
        os.replace(temporary, final)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise


def write_or_fallback(target: str | Path, write: Callable[[Path], object]) -> Path:
    """write(target); when that fails (a full disk, a folder removed meanwhile), write(a file
    in the temporary folder) so that the results are not lost, and raise OSError naming both."""
    target = Path(target)
    try:
        write(target)
        return target
    except OSError as error:
        fallback = Path(tempfile.gettempdir()) / f"syssimx-{os.getpid()}-{target.name}"
        write(fallback)
        raise OSError(f"cannot write {target} ({error}); the results were written to "
                      f"{fallback} instead") from error
