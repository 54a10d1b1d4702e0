"""SysSimX's components for other simulators, whose packages this platform does not have.

FEMComponent (NGSolve structural dynamics) and OpenSimComponent (OpenSim musculoskeletal
models) are importable so that SysSimX code imports; constructing one raises
ModuleNotFoundError naming the package it needs.
"""

from __future__ import annotations

import importlib.util
from typing import Any, NoReturn

from .base import CoSimComponent


def _unavailable(component: str, package: str, what: str) -> NoReturn:
    if importlib.util.find_spec(package) is None:
        raise ModuleNotFoundError(
            f"{component} needs the {package!r} package ({what}), which is not installed; "
            f"syssimx runs FMUs (FMUComponent) and Python components (CoSimComponent)",
            name=package)
    raise ModuleNotFoundError(
        f"{component} ({what}) is not part of syssimx, although {package!r} is installed; "
        "export the model as an FMI 2.0 Co-Simulation FMU and use FMUComponent", name=package)


class FEMComponent(CoSimComponent):
    """SysSimX's NGSolve transient structural FEM component (needs ngsolve)."""

    def __init__(self, name: str, *args: Any, **kwargs: Any) -> None:
        _unavailable("FEMComponent", "ngsolve", "NGSolve transient structural dynamics")


class OpenSimComponent(CoSimComponent):
    """SysSimX's OpenSim musculoskeletal component (needs opensim)."""

    def __init__(self, name: str, *args: Any, **kwargs: Any) -> None:
        _unavailable("OpenSimComponent", "opensim", "OpenSim musculoskeletal models")
