"""FMU files kept loaded in a worker process across the members it runs.

A component extracts its FMU (shared per file while some component of it lives) and the
engine dlopens the binary; both are released when the member's System is collected. A worker
runs member after member, so it keeps one extraction and one handle on each binary for its
whole life: later members find the archive extracted and the library mapped. FMUs that may be
instantiated only once per process keep their private extraction per instance, and isolated
components load the binary in their own host process: neither is kept here.
"""

from __future__ import annotations

import ctypes
import os
from dataclasses import dataclass
from pathlib import Path

from ..components.fmu import FMUComponent
from ..fmu.extraction import extractions
from ..system.system import System


@dataclass
class KeptFMU:
    directory: Path
    library: ctypes.CDLL
    members: int = 0
    extractions: int = 1  # extractions made for this file in this process (1 when all reuse)


class LoadedFMUs:
    """The FMU files this process keeps extracted and loaded, by resolved path."""

    def __init__(self) -> None:
        self._kept: dict[str, KeptFMU] = {}
        os.register_at_fork(after_in_child=self._kept.clear)

    def keep(self, system: System) -> None:
        """Keep the FMUs of a member's system, and count what it reused."""
        for component in system.components.values():
            if not isinstance(component, FMUComponent) or component.isolated or getattr(
                    component.info.description.coSimulation,
                    "canBeInstantiatedOnlyOncePerProcess", False):
                continue
            path = component.fmu_path
            kept = self._kept.get(path)
            if kept is None:
                directory, _ = extractions.acquire(Path(path), shareable=True)
                binary = directory / component.info.binary_name()
                kept = self._kept[path] = KeptFMU(directory, ctypes.CDLL(str(binary)))
            elif component._unzip_dir != kept.directory:
                kept.extractions += 1
            kept.members += 1

    def summary(self) -> dict[str, tuple[int, int]]:
        """{FMU file: (members that used it, extractions made)} in this process."""
        return {path: (kept.members, kept.extractions) for path, kept in self._kept.items()}


loaded_fmus = LoadedFMUs()
