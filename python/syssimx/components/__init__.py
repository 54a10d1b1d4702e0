"""Components: the base class, pure Python components, FMU components, table sources and
model switching."""

from .base import ComponentCheckpoint, CoSimComponent
from .fmu import FMUComponent
from .fmu_instance import FMUInstance, FMUState
from .multi import ModeSwitchEvent, MultiComponent
from .optional import FEMComponent, OpenSimComponent
from .switch_regions import SwitchRegions
from .table_source import TableSource

__all__ = ["CoSimComponent", "ComponentCheckpoint", "FEMComponent", "FMUComponent",
           "FMUInstance", "FMUState", "ModeSwitchEvent", "MultiComponent", "OpenSimComponent",
           "SwitchRegions", "TableSource"]
