"""Systems of components: connections, algorithms, results."""

from .algorithms import GaussSeidelAlgorithm, HybridAlgorithm, IJCSAAlgorithm, JacobiAlgorithm
from .connection import Connection, EventConnection
from .loader import ConfigError, build_system, load_config, run_from_config
from .results import EventRecord, LocalizationTrial, SimulationResult, Statistics
from .system import System
from .system_history import SystemHistory
from .termination import Termination

__all__ = ["ConfigError", "Connection", "EventConnection", "EventRecord",
           "GaussSeidelAlgorithm", "HybridAlgorithm", "IJCSAAlgorithm", "JacobiAlgorithm",
           "LocalizationTrial", "SimulationResult", "Statistics", "System", "SystemHistory",
           "Termination", "build_system", "load_config", "run_from_config"]
