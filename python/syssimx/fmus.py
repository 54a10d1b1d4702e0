"""The FMUs built by the syssimx toolchain and shipped with the package.

>>> from syssimx import fmus
>>> fmus.path("pendulum_cvode")   # doctest: +SKIP
'.../syssimx/fmus/pendulum_cvode.fmu'
"""

from __future__ import annotations

from ._paths import fmu_dir, installed_from_build
from .core.suggest import did_you_mean
from .errors import BundledFMUNotFoundError


def available() -> list[str]:
    """Names of the bundled FMUs (file names without .fmu), sorted. In a meson build (see
    SYSSIMX_BUILD_DIR) those the build installs: its test fixtures are no bundled FMUs."""
    directory = fmu_dir()
    if not directory.is_dir():
        return []
    installed = installed_from_build()
    return sorted(p.stem for p in directory.glob("*.fmu")
                  if installed is None or str(p.resolve()) in installed)


def path(name: str) -> str:
    """Absolute path of the bundled FMU `name`, e.g. "pendulum_euler"."""
    candidate = fmu_dir() / f"{name}.fmu"
    # only this one file is checked: a chain of 10 000 components asks 10 000 times
    installed = installed_from_build()
    if not candidate.is_file() or (installed is not None
                                   and str(candidate.resolve()) not in installed):
        names = available()
        raise BundledFMUNotFoundError(
            f"no bundled FMU named {name!r}{did_you_mean(name, names)}; "
            f"syssimx.fmus.available() lists the {len(names)} bundled FMUs")
    return str(candidate)
