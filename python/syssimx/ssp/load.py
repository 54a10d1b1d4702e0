"""syssimx.ssp.load: a System from an .ssp archive or an .ssd file."""

from __future__ import annotations

import shutil
import weakref
from dataclasses import dataclass
from pathlib import Path

from ..ssp_format.archive import open_package
from ..ssp_format.experiment import Experiment
from ..ssp_format.unsupported import Unsupported
from ..system.system import System
from .build import build
from .structure import read_structure


@dataclass(frozen=True)
class Imported:
    """A system read from an SSP and the experiment it proposes."""

    system: System
    experiment: Experiment


def load(path: str | Path, strict: bool = False) -> System:
    """The System an .ssp or .ssd file describes, not initialized. Each unsupported element
    and each name that names nothing gives one SSPWarning naming it (an SSPError with
    `strict`); a problem is an SSPError naming the file and the element."""
    return read(path, strict).system


def read(path: str | Path, strict: bool = False) -> Imported:
    """The system and the default experiment (start, stop, fixed step) of an .ssp or .ssd."""
    package = open_package(path)
    unsupported = Unsupported(strict)
    try:
        structure = read_structure(package, unsupported)
        system = build(structure, unsupported)
    except BaseException:
        if package.temporary is not None:
            shutil.rmtree(package.temporary, ignore_errors=True)
        raise
    if package.temporary is not None:  # the FMUs stay readable (to_ssp) while the system lives
        weakref.finalize(system, shutil.rmtree, package.temporary, True)
    return Imported(system, structure.experiment)
