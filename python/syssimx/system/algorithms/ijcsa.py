"""IJCSA (interface Jacobian-based co-simulation, Sicklinger et al. 2014) under SysSimX's name.

SysSimX's IJCSAAlgorithm solves every zero-delay interface input by one global Newton
iteration on u = y(u) at each communication point, then steps the components in dependency
order. The engine's Gauss-Seidel coupling does exactly that in C: direct-feedthrough outputs
propagate in schedule order, and every algebraic loop is solved by Newton at the end of each
macro step (the start of the next one), with the interface Jacobian from
fmi2GetDirectionalDerivative where the FMU provides it. IJCSAAlgorithm is that coupling with
SysSimX's option names: `tol` is the loop tolerance (`tolerance`), `max_iter` its iterations.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .coupling import GaussSeidelAlgorithm


@dataclass(init=False)
class IJCSAAlgorithm(GaussSeidelAlgorithm):
    """Gauss-Seidel coupling with every algebraic loop solved by Newton; `tol` and
    `max_iter` as in SysSimX (defaults: the engine's loop options of GaussSeidelAlgorithm)."""

    name: str = field(default="IJCSA")

    def __init__(self, max_iter: int | None = None, tol: float | None = None, *,
                 damping: float | None = None, loop_jacobian: str | None = None,
                 threads: int | None = None, name: str = "IJCSA") -> None:
        super().__init__(name=name)
        if max_iter is not None:
            self.max_iter = max_iter
        if tol is not None:
            self.tolerance = tol
        if damping is not None:
            self.damping = damping
        if loop_jacobian is not None:
            self.loop_jacobian = loop_jacobian
        if threads is not None:
            self.threads = threads

    @property
    def tol(self) -> float:
        """SysSimX's name of the loop tolerance."""
        return self.tolerance

    @tol.setter
    def tol(self, value: float) -> None:
        self.tolerance = value
