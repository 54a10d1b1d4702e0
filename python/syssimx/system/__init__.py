"""Systems of components: connections, algorithms, results."""

from .algorithms import GaussSeidelAlgorithm, HybridAlgorithm, JacobiAlgorithm
from .connection import Connection, EventConnection
from .results import EventRecord, LocalizationTrial, SimulationResult, Statistics, SystemHistory
from .system import System
from .termination import Termination

__all__ = ["Connection", "EventConnection", "EventRecord", "GaussSeidelAlgorithm",
           "HybridAlgorithm", "JacobiAlgorithm", "LocalizationTrial", "SimulationResult",
           "Statistics", "System", "SystemHistory", "Termination"]
