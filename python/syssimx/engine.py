"""The cffi binding of the C engine: the only bridge between Python and C.

Out-of-line ABI mode: the build generates the `ffi` module from the engine header
(src/engine_ffi.py), so importing syssimx parses no C; the shared library is opened on first
use, and refused if it was built from another header than the module.
"""

from __future__ import annotations

from functools import cache, lru_cache
from importlib.machinery import SourceFileLoader
from types import ModuleType
from typing import Any

from . import _paths
from .errors import EngineMismatchError

_MODULE = "syssimx._engine_ffi"


def _interface() -> ModuleType:
    path = _paths.engine_ffi_module()
    module = ModuleType(_MODULE)
    module.__file__ = str(path)
    SourceFileLoader(_MODULE, str(path)).exec_module(module)
    return module


_INTERFACE = _interface()
ffi = _INTERFACE.ffi


@lru_cache(maxsize=1)
def lib() -> Any:
    """The loaded engine library."""
    path = _paths.engine_library()
    library = ffi.dlopen(str(path))
    try:
        digest = ffi.string(library.ssx_interface_digest()).decode()
    except AttributeError:
        digest = "none (it does not export ssx_interface_digest)"
    if digest != _INTERFACE.INTERFACE_DIGEST:
        raise EngineMismatchError(
            f"the engine library {path} was built from another syssimx_engine.h than its cffi "
            f"module {_INTERFACE.__file__} (header digest {digest} against "
            f"{_INTERFACE.INTERFACE_DIGEST}): a stale build; rebuild both (meson compile, or "
            "pip install .)")
    return library


def string(pointer: Any) -> str:
    """A C string as str ("" for NULL)."""
    return "" if pointer == ffi.NULL else ffi.string(pointer).decode("utf-8", "replace")


def status_name(status: int) -> str:
    """The engine's name of a status an ssx_fmu call returned ("OK" ... "Pending", "failed"
    for -1); the number itself for any other."""
    name = lib().ssx_status_name(status)
    return str(status) if name == ffi.NULL else ffi.string(name).decode()


@cache
def enum_values(ctype: str, prefix: str) -> dict[str, int]:
    """An enum of the header by lower-case name without its prefix, in value order:
    enum_values("ssx_locator", "SSX_") maps "illinois" to SSX_ILLINOIS. The one dict per enum:
    read it, never change it."""
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
