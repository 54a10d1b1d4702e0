"""syssimx.osp.load: a System from an OspSystemStructure.xml (or the folder holding one)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..ssp_format.experiment import Experiment
from ..ssp_format.unsupported import Unsupported
from ..system.system import System
from .build import PowerBond, build
from .document import read_document, structure_file
from .ecco import ecco_algorithm
from .errors import OSPError, OSPWarning


@dataclass(frozen=True)
class OSPImported:
    """A system read from an OSP system structure, the experiment it proposes (StartTime,
    EndTime, BaseStepSize), its <Algorithm>, its power bonds and its <EccoConfiguration>
    (SafetyFactor, StepSize, MinimumStepSize, ... by element name)."""

    system: System
    experiment: Experiment
    algorithm: str
    power_bonds: list[PowerBond]
    ecco: dict[str, float]


def load(path: str | Path, strict: bool = False) -> System:
    """The System an OSP system structure describes, not initialized. What syssimx does not
    support is one OSPWarning naming it (an OSPError with `strict`); a problem is an OSPError
    naming the file and the element."""
    return read(path, strict).system


def read(path: str | Path, strict: bool = False,
         proxies_in_process: bool = False) -> OSPImported:
    """The system, experiment, algorithm and power bonds of an OSP system structure.
    proxies_in_process: a proxy FMU (proxyfmu://) runs in this process, not isolated."""
    document = read_document(structure_file(path))
    unsupported = Unsupported(strict, OSPError, OSPWarning)
    for element in document.ignored:
        unsupported.warn(f"the element {element.split(' ')[0]}", f"{document.path}: {element}")
    system, bonds = build(document, unsupported, proxies_in_process)
    if document.algorithm == "ecco":
        if not bonds:
            unsupported.warn("<Algorithm> ecco without power bonds",
                             f"{document.path}: no connection has a powerBond, so the steps "
                             "adapt to the coupling error of every connection instead of an "
                             "energy residual")
        system.set_algorithm(ecco_algorithm(document.ecco, bonds, str(document.path)))
    return OSPImported(system, Experiment(document.start_time, document.end_time,
                                          document.base_step), document.algorithm, bonds,
                       document.ecco)
