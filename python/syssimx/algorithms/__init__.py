"""The master algorithms under SysSimX's namespace (`syssimx.algorithms`, also
`syssimx.system.algorithms`): Jacobi, Gauss-Seidel, IJCSA and the hybrid algorithm, and the
step control a coupling may take."""

from ..system.algorithms import (
    Algorithm,
    GaussSeidelAlgorithm,
    HybridAlgorithm,
    IJCSAAlgorithm,
    JacobiAlgorithm,
    StepControl,
)

__all__ = ["Algorithm", "GaussSeidelAlgorithm", "HybridAlgorithm", "IJCSAAlgorithm",
           "JacobiAlgorithm", "StepControl"]
