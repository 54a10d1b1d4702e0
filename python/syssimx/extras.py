"""Which optional extra provides which library: the one table, and the import that names the
extra to install when the library is missing."""

from __future__ import annotations

import importlib
from types import ModuleType

from .errors import MissingDependencyError

# library (its import name) -> the syssimx extra that installs it
EXTRAS = {
    "pandas": "results",
    "pyarrow": "results",
    "graphviz": "viz",
    "dask": "ensemble",
    "distributed": "ensemble",
    "xarray": "ensemble",
    "scipy": "ensemble",  # the .nc writer
}


def install_hint(library: str) -> str:
    """`pip install "syssimx-engine[extra]"` for a library of EXTRAS, else `pip install library`."""
    extra = EXTRAS.get(library.split(".")[0])
    return f'pip install "syssimx-engine[{extra}]"' if extra else f"pip install {library}"


def require(library: str, purpose: str) -> ModuleType:
    """Import `library`; when it is missing, a MissingDependencyError says what needs it and
    which extra to install."""
    try:
        return importlib.import_module(library)
    except ModuleNotFoundError as error:
        top = library.split(".")[0]
        if error.name is not None and error.name.split(".")[0] != top:
            raise  # the library is there but broken: its own message says more
        raise MissingDependencyError(
            f"{purpose} needs {top}, which is not installed: {install_hint(top)}",
            name=top) from None
