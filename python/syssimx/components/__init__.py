"""Components: the base class, pure Python components, FMU components and table sources."""

from .base import CoSimComponent
from .fmu import FMUComponent
from .fmu_instance import FMUInstance, FMUState
from .table_source import TableSource

__all__ = ["CoSimComponent", "FMUComponent", "FMUInstance", "FMUState", "TableSource"]
