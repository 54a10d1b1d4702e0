"""syssimx: hybrid co-simulation of FMUs (FMI 1.0, 2.0 and 3.0, Co-Simulation and Model
Exchange), run by a C engine.

Build a System of FMUComponent and CoSimComponent objects, connect them, optionally add event
indicators and event connections, then initialize and run. The SysSimX API is kept.

Every name below is imported on first use: `import syssimx` loads none of the package, and a
program pays only for the parts it touches.
"""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING

from ._lazy import lazy_names
from .bridge.standalone import register_system_class

if TYPE_CHECKING:
    from .system.system import System as SystemClass

_MODULES = {
    "AlgebraicLoopError": ".errors",
    "CoSimComponent": ".components",
    "ComponentCheckpoint": ".components",
    "ConfigurationError": ".errors",
    "Connection": ".system",
    "DenseTime": ".core",
    "EventConnection": ".system",
    "FEMComponent": ".components",
    "FMUComponent": ".components",
    "FMUError": ".errors",
    "FMUFileError": ".errors",
    "GaussSeidelAlgorithm": ".system",
    "HybridAlgorithm": ".system",
    "IJCSAAlgorithm": ".system",
    "JacobiAlgorithm": ".system",
    "ModeSwitchEvent": ".components",
    "MultiComponent": ".components",
    "OpenSimComponent": ".components",
    "Port": ".core",
    "PortSpec": ".core",
    "PortType": ".core",
    "Reinitialize": ".components",
    "ScheduledExecutionComponent": ".components",
    "SimulationError": ".errors",
    "SimulationResult": ".system",
    "SimulationTimeoutError": ".errors",
    "StateError": ".errors",
    "StepControl": ".system",
    "SwitchRegions": ".components",
    "SysSimXError": ".errors",
    "System": ".system",
    "SystemState": ".system",
    "SystemGraphVisualizer": ".viz.system_graph_visualizer",  # needs the optional graphviz
    "TableSource": ".components",
    "Termination": ".system",
    "ZenoError": ".errors",
    "algorithms": ".algorithms",
    "osp": ".osp",  # OSP system structures: syssimx.osp.load(path)
    "ssp": ".ssp",  # SSP files: syssimx.ssp.load(path)
    "__version__": "._version",
    "__version_info__": "._version",
}

__all__ = list(_MODULES)

__getattr__, __dir__ = lazy_names(__name__, _MODULES)


def _new_system(name: str) -> SystemClass:
    """A component used on its own runs in a System: imported only then."""
    from .system.system import System

    return System(name)


register_system_class(_new_system)

logging.getLogger(__name__).addHandler(logging.NullHandler())
