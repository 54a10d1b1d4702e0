"""Coupling algorithms for continuous systems and their algebraic-loop options."""

from __future__ import annotations

from dataclasses import dataclass

LOOP_JACOBIANS = ("auto", "finite_differences")


@dataclass
class JacobiAlgorithm:
    """Every component steps from the inputs of the start of the macro step.

    tolerance, max_iter and damping configure the solution of algebraic loops at each
    communication point. loop_jacobian: "auto" takes Newton's Jacobian from
    fmi2GetDirectionalDerivative for the inputs of FMUs that provide it and from finite
    differences elsewhere; "finite_differences" uses finite differences throughout."""

    tolerance: float = 1e-10
    max_iter: int = 100
    damping: float = 1.0
    name: str = "Jacobi"
    loop_jacobian: str = "auto"

    def validate(self) -> None:
        if self.loop_jacobian not in LOOP_JACOBIANS:
            raise ValueError(f"{self.name}: loop_jacobian must be one of {LOOP_JACOBIANS}, "
                             f"got {self.loop_jacobian!r}")
        if not self.tolerance > 0 or self.max_iter < 1 or not 0 < self.damping <= 1:
            raise ValueError(f"{self.name}: tolerance > 0, max_iter >= 1 and 0 < damping <= 1 "
                             f"are required (got {self.tolerance}, {self.max_iter}, "
                             f"{self.damping})")


@dataclass
class GaussSeidelAlgorithm(JacobiAlgorithm):
    """Components step in dependency order; a consumer of a direct-feedthrough output gets
    the value of the same communication point (the default)."""

    name: str = "Gauss-Seidel"
