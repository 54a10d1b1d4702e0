"""System files other tools write, by kind: SSP (.ssp archive, .ssd) and OSP system structures
(.xml, or a folder holding OspSystemStructure.xml). `run` and `describe` read them here."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    from .ssp_format.experiment import Experiment
    from .system.system import System

SSP_SUFFIXES = (".ssp", ".ssd")
OSP_SUFFIXES = (".xml",)


def is_system_file(path: str | Path) -> bool:
    """Whether `path` is an SSP or OSP file (by its suffix), or a folder with an OSP structure."""
    path = Path(path)
    if path.is_dir():
        return (path / "OspSystemStructure.xml").is_file()
    return path.suffix.lower() in SSP_SUFFIXES + OSP_SUFFIXES


class SystemFile(Protocol):
    """What a front-end reads from a file: the system and the experiment it proposes."""

    @property
    def system(self) -> System: ...

    @property
    def experiment(self) -> Experiment: ...


def read_system_file(path: str | Path, strict: bool = False,
                     proxies_in_process: bool = False) -> SystemFile:
    """The imported system and experiment of an SSP or OSP file. proxies_in_process: an OSP
    file's proxy FMUs run in this process, not isolated (what an exported FMU can carry)."""
    if Path(path).suffix.lower() in SSP_SUFFIXES:
        from .ssp import read

        return read(path, strict)
    from .osp import read as read_osp

    return read_osp(path, strict, proxies_in_process)
