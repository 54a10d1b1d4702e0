"""The FMUs built by the syssimx toolchain and shipped with the package.

>>> from syssimx import fmus
>>> fmus.path("pendulum_cvode")   # doctest: +SKIP
'.../syssimx/fmus/pendulum_cvode.fmu'
"""

from __future__ import annotations

from ._paths import fmu_dir
from .core.suggest import did_you_mean
from .errors import BundledFMUNotFoundError


def available() -> list[str]:
    """Names of the bundled FMUs (file names without .fmu), sorted."""
    directory = fmu_dir()
    return sorted(p.stem for p in directory.glob("*.fmu")) if directory.is_dir() else []


def path(name: str) -> str:
    """Absolute path of the bundled FMU `name`, e.g. "pendulum_euler"."""
    candidate = fmu_dir() / f"{name}.fmu"
    if not candidate.is_file():
        names = available()
        raise BundledFMUNotFoundError(
            f"no bundled FMU named {name!r}{did_you_mean(name, names)}; "
            f"syssimx.fmus.available() lists the {len(names)} bundled FMUs")
    return str(candidate)
