"""Where a member's System comes from: a picklable function, or a system description file.

Both are callables that build a fresh System in the worker process; a
worker never receives a System object (FMU instances are native and cannot be pickled).
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import ConfigurationError
from ..system.system import System

SYSTEM_FILE_SUFFIXES = (".yaml", ".yml", ".json")

SystemSource = Callable[[], System]


@dataclass(frozen=True)
class SystemFile:
    """A YAML/JSON system description, read in the worker (the file and the FMUs it names
    must be on a path every worker sees). allowed_modules: where its `class:` entries may come
    from besides syssimx (see system/component_classes.py)."""

    path: str
    allowed_modules: tuple[str, ...] = ()

    def __call__(self) -> System:
        from ..system.loader import build_system

        return build_system(self.path, allowed_modules=self.allowed_modules)

    def run_settings(self) -> dict[str, float]:
        """The description's `run` entry (t0, tf, dt), read here in the client."""
        from ..system.loader import load_config

        run = load_config(self.path).get("run") or {}
        return {key: value for key, value in run.items() if key in ("t0", "tf", "dt")}


@dataclass(frozen=True)
class ShippedFunction:
    """A system function sent by value (cloudpickle), for one defined in a file the workers
    cannot import: Dask pickles an importable-here function by reference."""

    payload: bytes

    @classmethod
    def of(cls, function: SystemSource) -> ShippedFunction:
        import cloudpickle

        module = sys.modules[function.__module__]
        cloudpickle.register_pickle_by_value(module)
        try:
            return cls(cloudpickle.dumps(function))
        finally:
            cloudpickle.unregister_pickle_by_value(module)

    def __call__(self) -> System:
        import cloudpickle

        return cloudpickle.loads(self.payload)()


def system_source(system: Any, allowed_modules: tuple[str, ...] = ()) -> SystemSource:
    """A system file path (str or Path ending in .yaml, .yml or .json) or a callable."""
    if isinstance(system, SystemFile):
        return system
    if isinstance(system, str | Path):
        path = Path(system)
        if path.suffix.lower() not in SYSTEM_FILE_SUFFIXES:
            raise ConfigurationError(f"{path}: a system file ends in "
                                     f"{', '.join(SYSTEM_FILE_SUFFIXES)}")
        if not path.is_file():
            raise ConfigurationError(f"{path}: no such system file")
        return SystemFile(str(path.resolve()), allowed_modules)
    if isinstance(system, System):
        raise ConfigurationError("an ensemble needs a function that builds the System (each "
                                 "member builds its own in a worker process), not a System")
    if not callable(system):
        raise ConfigurationError(f"system must be a system file or a function returning a "
                                 f"System, got {type(system).__name__} {system!r}")
    return system
