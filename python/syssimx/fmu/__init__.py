"""FMU files: the archive (checked, extracted), its modelDescription read per FMI version, the
binary loaded into the engine, and the instance proxy. The FMI version is decided once, where
the description is read (description.py); the rest asks the FMU's standard (standards.py).
Components that run an FMU (components/fmu.py) build on this package."""

from .._lazy import lazy_names

_MODULES = {
    "FMUInfo": ".info",
    "FMUInstance": ".instance",
    "FMUState": ".instance",
    "read_fmu": ".info",
}

__all__ = list(_MODULES)

__getattr__, __dir__ = lazy_names(__name__, _MODULES)
