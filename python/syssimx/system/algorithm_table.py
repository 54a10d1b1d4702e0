"""The master algorithms by the name a system description or the command line gives them: the
one table both read. Names only here, so that the command line's usage loads no engine."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .algorithms import Algorithm

ALGORITHM_CLASSES = {
    "jacobi": "JacobiAlgorithm",
    "gauss_seidel": "GaussSeidelAlgorithm",
    "hybrid": "HybridAlgorithm",
    "ijcsa": "IJCSAAlgorithm",
}
ALGORITHM_NAMES = tuple(ALGORITHM_CLASSES)


def algorithm_class(name: str) -> Callable[..., Algorithm]:
    """The class of the algorithm called `name` (one of ALGORITHM_NAMES)."""
    from . import algorithms

    algorithm: Callable[..., Algorithm] = getattr(algorithms, ALGORITHM_CLASSES[name])
    return algorithm
