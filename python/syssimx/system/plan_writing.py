"""A System written as a plan: the records its engine system is built from, its algorithm's
options and initialize's settings as they are now, and what initializes each FMU (its
experiment, the parameters the user set, its engine restart), so that the engine alone can
build, initialize and run it."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ..atomic_file import atomic_path
from ..bridge.plan import EnginePlan
from ..plan.writer import with_folders
from .algorithms import HybridAlgorithm
from .plan_options import option_records, setting_records


def plan_text(plan: EnginePlan, algorithm: Any, power_bond_ends: list[int],
              folders: Mapping[str, str | Path] | None) -> str:
    """The text of a built `plan` run by `algorithm`, each FMU in `folders[name]` (else where
    syssimx unpacked it)."""
    settings = plan.initialize_settings or (0, None)
    initialization = [c._plan_initialization(plan.index[name])
                      for name, c in plan.components.items()
                      if hasattr(c, "_plan_initialization")]
    records = plan.records.extended(option_records(algorithm, power_bond_ends),
                                    setting_records(settings), *initialization)
    return (with_folders(records, folders) if folders else records).text()


def coupling_of(algorithm: Any) -> Any:
    """The coupling algorithm of an algorithm (itself, or a hybrid algorithm's)."""
    return algorithm.coupling if isinstance(algorithm, HybridAlgorithm) else algorithm


def write_text(path: str | Path, text: str) -> Path:
    """`text` into the file `path`, whole or not at all."""
    with atomic_path(path) as temporary:
        temporary.write_text(text, encoding="utf-8")
    return Path(path)

