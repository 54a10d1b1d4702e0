"""The master algorithms under SysSimX's namespace (`syssimx.algorithms`, also
`syssimx.system.algorithms`): Jacobi, Gauss-Seidel, IJCSA and the hybrid algorithm."""

from ..system.algorithms import (
    Algorithm,
    GaussSeidelAlgorithm,
    HybridAlgorithm,
    IJCSAAlgorithm,
    JacobiAlgorithm,
)

__all__ = ["Algorithm", "GaussSeidelAlgorithm", "HybridAlgorithm", "IJCSAAlgorithm",
           "JacobiAlgorithm"]
