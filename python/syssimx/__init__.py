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
__version_info__ = tuple(int(part) for part in __version__.split("."))

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
    "SystemGraphVisualizer",
    "TableSource",
    "Termination",
    "ZenoError",
    "__version__",
    "__version_info__",
    "algorithms",
]


def __getattr__(name: str) -> object:
    """SystemGraphVisualizer is imported on first use: it needs the optional graphviz."""
    if name == "SystemGraphVisualizer":
        from .viz.system_graph_visualizer import SystemGraphVisualizer

        return SystemGraphVisualizer
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

logging.getLogger(__name__).addHandler(logging.NullHandler())
