"""Components: the base class, pure Python components and FMU components."""

from .base import CoSimComponent
from .fmu import FMUComponent
from .fmu_instance import FMUInstance, FMUState

__all__ = ["CoSimComponent", "FMUComponent", "FMUInstance", "FMUState"]
