"""Master algorithms: how the engine couples components and handles events."""

from .coupling import GaussSeidelAlgorithm, JacobiAlgorithm
from .hybrid import HybridAlgorithm
from .ijcsa import IJCSAAlgorithm
from .step_control import StepControl

Algorithm = JacobiAlgorithm | GaussSeidelAlgorithm | HybridAlgorithm

__all__ = ["Algorithm", "GaussSeidelAlgorithm", "HybridAlgorithm", "IJCSAAlgorithm",
           "JacobiAlgorithm", "StepControl"]
