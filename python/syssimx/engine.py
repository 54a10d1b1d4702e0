"""The cffi binding of the C engine: the only bridge between Python and C.

ABI mode: the cdef is the engine header with its preprocessor lines removed, and the shared
library is opened on first use.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

from cffi import FFI

from . import _paths

ffi = FFI()


def _cdef_text() -> str:
    header = _paths.engine_header().read_text()
    return "\n".join(line for line in header.splitlines() if not line.lstrip().startswith("#"))


ffi.cdef(_cdef_text())


@lru_cache(maxsize=1)
def lib() -> Any:
    """The loaded engine library."""
    return ffi.dlopen(str(_paths.engine_library()))


def string(pointer: Any) -> str:
    """A C string as str ("" for NULL)."""
    return "" if pointer == ffi.NULL else ffi.string(pointer).decode("utf-8", "replace")


def status_name(status: int) -> str:
    """The engine's name of a status an ssx_fmu call returned ("OK" ... "Pending", "failed"
    for -1); the number itself for any other."""
    name = lib().ssx_status_name(status)
    return str(status) if name == ffi.NULL else ffi.string(name).decode()


def enum_values(ctype: str, prefix: str) -> dict[str, int]:
    """An enum of the header by lower-case name without its prefix, in value order:
    enum_values("ssx_locator", "SSX_") maps "illinois" to SSX_ILLINOIS."""
    return {name.removeprefix(prefix).lower(): value
            for value, name in sorted(ffi.typeof(ctype).elements.items())}


def enum_name(ctype: str, prefix: str, value: int) -> str:
    """The lower-case name of an enum value, without its prefix (the inverse of enum_values)."""
    return ffi.typeof(ctype).elements[value].removeprefix(prefix).lower()


@lru_cache(maxsize=1)
def defaults() -> Any:
    """The engine's ssx_defaults: the one definition of every option's default."""
    out = ffi.new("ssx_defaults *")
    lib().ssx_get_defaults(out)
    return out
