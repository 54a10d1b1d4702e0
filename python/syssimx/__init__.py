"""syssimx: hybrid co-simulation of FMI 2.0 Co-Simulation FMUs, run by a C engine.

Build a System of FMUComponent and CoSimComponent objects, connect them, optionally add event
indicators and event connections, then initialize and run. The SysSimX API is kept.
"""

import logging

from . import algorithms
from .components import (
    ComponentCheckpoint,
    CoSimComponent,
    FEMComponent,
    FMUComponent,
    ModeSwitchEvent,
    MultiComponent,
    OpenSimComponent,
    SwitchRegions,
    TableSource,
)
from .core import DenseTime, Port, PortSpec, PortType
from .errors import (
    AlgebraicLoopError,
    ConfigurationError,
    FMUError,
    FMUFileError,
    SimulationError,
    SimulationTimeoutError,
    SysSimXError,
    ZenoError,
)
from .system import (
    Connection,
    EventConnection,
    GaussSeidelAlgorithm,
    HybridAlgorithm,
    IJCSAAlgorithm,
    JacobiAlgorithm,
    SimulationResult,
    System,
    Termination,
)

__version__ = "0.1.0"

__all__ = [
    "AlgebraicLoopError",
    "CoSimComponent",
    "ComponentCheckpoint",
    "ConfigurationError",
    "Connection",
    "DenseTime",
    "EventConnection",
    "FEMComponent",
    "FMUComponent",
    "FMUError",
    "FMUFileError",
    "GaussSeidelAlgorithm",
    "HybridAlgorithm",
    "IJCSAAlgorithm",
    "JacobiAlgorithm",
    "ModeSwitchEvent",
    "MultiComponent",
    "OpenSimComponent",
    "Port",
    "PortSpec",
    "PortType",
    "SimulationError",
    "SimulationResult",
    "SimulationTimeoutError",
    "SwitchRegions",
    "SysSimXError",
    "System",
    "TableSource",
    "Termination",
    "ZenoError",
    "__version__",
    "algorithms",
]

logging.getLogger(__name__).addHandler(logging.NullHandler())
