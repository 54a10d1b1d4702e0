"""Checks that an output file can be written, made before a run so that a run's results are
never computed and then lost to a missing folder, a read-only one or a writer that is not
installed."""

from __future__ import annotations

import importlib.util
import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from .atomic_file import is_special, resolved_target
from .errors import ConfigurationError

# suffix -> the modules of which one must be importable to write it, and what to install
_WRITERS: dict[str, tuple[tuple[str, ...], str]] = {
    ".parquet": (("pyarrow", "fastparquet"), "pyarrow or fastparquet"),
    ".nc": (("scipy", "netCDF4", "h5netcdf"), 'scipy (pip install "syssimx-engine[ensemble]")'),
}


def check_output(path: str | Path, what: str = "output",
                 suffixes: Iterable[str] | None = None, writer: str | None = None) -> Path:
    """`path`, after checking that a file can be written there: its folder exists and is
    writable, it is not a folder, its suffix is one of `suffixes` (when given) and the writer
    of its format (by its suffix, or the module `writer`) is installed. ConfigurationError
    naming the path and what is wrong."""
    target = Path(path)
    suffix = target.suffix.lower()
    if suffixes is not None:
        known = tuple(suffixes)
        if suffix not in known:
            raise ConfigurationError(f"{what} {target}: unknown format {suffix or '(none)'!r}; "
                                     f"use one of {', '.join(known)}")
    if is_special(target):  # a device or FIFO: written directly, whatever its folder allows
        if not os.access(target, os.W_OK):
            raise ConfigurationError(f"{what} {target} is not writable")
    else:
        _check_file(target, what)
    modules, install = ((writer,), writer) if writer is not None \
        else _WRITERS.get(suffix, ((), ""))
    if modules and not any(importlib.util.find_spec(m) is not None for m in modules):
        raise ConfigurationError(f"{what} {target}: writing {suffix or 'it'} needs {install}, "
                                 "which is not installed")
    return target


def check_command_outputs(args: Any) -> None:
    """The files a command line asks for (--output, --plot), checked before anything runs."""
    output = getattr(args, "output", None)
    if output is not None:
        suffixes = None
        if getattr(args, "command", None) == "sweep":
            from .ensemble.result import WRITERS

            suffixes = WRITERS
        check_output(output, "output", suffixes)
    plot = getattr(args, "plot", None)
    if plot is not None:  # a PNG whatever its name
        check_output(plot, "plot", writer="matplotlib")


def _check_file(target: Path, what: str) -> None:
    """A regular file (or none yet) at `target`, written through its links: its folder."""
    folder = resolved_target(target).parent
    if not folder.is_dir():
        raise ConfigurationError(f"{what} {target}: the folder {folder} does not exist")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise ConfigurationError(f"{what} {target}: the folder {folder} is not writable")
    if target.is_dir():
        raise ConfigurationError(f"{what} {target} is a folder, not a file")
    if target.exists() and not os.access(target, os.W_OK):
        raise ConfigurationError(f"{what} {target} exists and is not writable")
