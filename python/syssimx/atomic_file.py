"""Output files appear whole or not at all.

Every file syssimx writes for a user (CSV, NetCDF, Parquet, SSP archives, plots, graphs) is
written to a temporary name in the target's folder and renamed onto the target once complete:
a rename within one file system is atomic, so a reader, a SIGTERM or a full disk never leaves a
truncated file under the target's name. What an interrupted write leaves is a hidden
``.<name>.<random>.partial<suffix>`` beside it, removed when the write fails in Python.
"""

from __future__ import annotations

import os
import secrets
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path


@contextmanager
def atomic_path(target: str | Path) -> Iterator[Path]:
    """A fresh temporary path beside `target` (same suffix, so writers that choose a format by
    it still do) to write to; renamed onto `target` when the block ends normally, removed when
    it raises."""
    target = Path(target)
    temporary = target.with_name(f".{target.stem}.{secrets.token_hex(4)}.partial{target.suffix}")
    # created here, honouring the umask, so the file ends with the mode a direct write gives
    os.close(os.open(temporary, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o666))
    try:
        yield temporary
        os.replace(temporary, target)
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
