"""Loading an FMU's binary into the engine: one call (ssx_fmu_load) with a load spec that the
FMU's standard writes."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from .._paths import fmu_host
from ..engine import ffi, lib
from ..errors import FMUFileError
from .extraction import extractions
from .info import FMUInfo, FMUInterface


def load(info: FMUInfo, interface: FMUInterface, name: str, isolated: bool,
         step_timeout: float | None) -> tuple[Any, Path, tuple[str, int, int] | None]:
    """Extract the archive (shared where FMI allows) and load the interface's binary into the
    engine, or into a host process of its own when isolated (no instance yet). Returns the
    engine's ssx_fmu, the extraction folder and its key (for extractions.release)."""
    once_per_process = interface.can_be_instantiated_only_once_per_process
    # every isolated FMU has a process of its own, so it may share the extraction
    unzip_dir, key = extractions.acquire(info.path, shareable=isolated or not once_per_process)
    binary_name = info.binary_name(interface.name)
    binary = extractions.binary(unzip_dir, binary_name)
    if binary is None:
        extractions.release(unzip_dir, key)
        raise FMUFileError(f"{info.path}: {binary_name} is not a file inside the "
                           "extracted archive; refused to load it")
    error = ffi.new("char[1024]")
    try:
        spec, _pointed_at = info.standard.load_spec(info, interface, binary, unzip_dir, name,
                                                    fmu_host() if isolated else None,
                                                    step_timeout)
    except BaseException:
        # a refused description (a clock the interface cannot tick, ...) holds no extraction
        extractions.release(unzip_dir, key)
        raise
    # the components of one shared extraction make their bindings side by side
    spec.binding_pool = ffi.NULL if key is None else extractions.shared(key, _binding_pool)
    handle = lib().ssx_fmu_load(spec, error, 1024)
    if handle == ffi.NULL:
        extractions.release(unzip_dir, key)
        raise FMUFileError(f"{info.path}: cannot load {binary_name}: "
                           f"{ffi.string(error).decode(errors='replace')}")
    return handle, unzip_dir, key


def _binding_pool() -> Any:
    """A pool for the engine's bindings, released when Python lets it go (its bindings keep it
    until they are freed); NULL, which loads each binding on its own, when out of memory."""
    pool = lib().ssx_binding_pool_new()
    return ffi.NULL if pool == ffi.NULL else ffi.gc(pool, lib().ssx_binding_pool_release)
