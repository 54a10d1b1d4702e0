"""Components: the base class, pure Python components, FMU components, table sources and
model switching (each imported on first use)."""

from .._lazy import lazy_names

_MODULES = {
    "CoSimComponent": ".base",
    "ComponentCheckpoint": ".base",
    "FEMComponent": ".optional",
    "FMUComponent": ".fmu",
    "FMUInstance": "..fmu.instance",  # the instance proxy lives with the FMU seam
    "FMUState": "..fmu.instance",
    "ModeSwitchEvent": ".multi",
    "MultiComponent": ".multi",
    "OpenSimComponent": ".optional",
    "Reinitialize": ".restart",
    "ScheduledExecutionComponent": ".scheduled_execution",
    "SwitchRegions": ".switch_regions",
    "TableSource": ".table_source",
}

__all__ = list(_MODULES)

__getattr__, __dir__ = lazy_names(__name__, _MODULES)
