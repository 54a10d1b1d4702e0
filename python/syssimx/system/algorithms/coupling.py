"""Coupling algorithms for continuous systems and their algebraic-loop options.

Every default is the engine's (ssx_get_defaults), and the engine judges the values."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

from ...bridge.options import engine_refusal
from ...engine import defaults, enum_name, enum_values, ffi, lib
from ...errors import ConfigurationError
from .signature import EngineDefaults
from .step_control import StepControl

JACOBIAN_PREFIX = "SSX_JACOBIAN_"


def loop_jacobians() -> dict[str, int]:
    """The engine's ways to build a loop's Jacobian by name: SSX_JACOBIAN_AUTO is "auto"."""
    return enum_values("ssx_loop_jacobian", JACOBIAN_PREFIX)


@dataclass
class JacobiAlgorithm:
    """Jacobi coupling: every component steps from the inputs of the start of the macro step.

    Every default is the engine's (``ssx_get_defaults``), and the engine judges the values.

    Parameters
    ----------
    tolerance : float
        Newton's tolerance for the algebraic loops solved at each communication point.
    max_iter : int
        Newton iterations per loop solve.
    damping : float
        Newton's step factor, 0 < damping <= 1.
    name : str
        The algorithm's name in reports.
    loop_jacobian : str
        ``"auto"`` takes Newton's Jacobian from ``fmi2GetDirectionalDerivative`` for the inputs
        of FMUs that provide it and from finite differences elsewhere;
        ``"finite_differences"`` uses finite differences throughout.
    threads : int
        FMU components step on this many threads in C (the calling thread and threads - 1
        workers, see ``ssx_set_threads``). Python components and FMUs that declare
        canBeInstantiatedOnlyOncePerProcess stay on the calling thread; the results are those
        of one thread.
    input_order : int
        0 holds every input over a communication step; 1 or 2 hands FMUs that declare
        canInterpolateInputs the first (and second) time derivative of each connected Real
        input, from the driving FMU's output derivatives where it declares them, else from the
        last communication points (see ``ssx_set_input_order``).
    extrapolate_held_inputs : bool
        With input_order 1 or 2, an FMU that cannot interpolate its inputs gets, instead of
        each input's value at the step's start, the mean of its polynomial over the step (the
        value at mid-step for order 1): second order in the step instead of first. An
        extrapolation may overshoot where a signal turns sharply (see
        ``ssx_set_extrapolate_held_inputs``).
    step_control : StepControl or None
        A StepControl chooses the communication steps by the coupling error; None steps on the
        run's grid.
    """

    tolerance: float = field(default_factory=lambda: defaults().loop_tolerance)
    max_iter: int = field(default_factory=lambda: defaults().loop_max_iterations)
    damping: float = field(default_factory=lambda: defaults().loop_damping)
    name: str = "Jacobi"
    loop_jacobian: str = field(default_factory=lambda: enum_name(
        "ssx_loop_jacobian", JACOBIAN_PREFIX, defaults().loop_jacobian))
    threads: int = field(default_factory=lambda: defaults().threads)
    input_order: int = field(default_factory=lambda: defaults().input_order)
    extrapolate_held_inputs: bool = field(
        default_factory=lambda: bool(defaults().extrapolate_held_inputs))
    step_control: StepControl | None = None
    engine_coupling: ClassVar[str] = "SSX_JACOBI"  # the ssx_coupling it runs as
    __signature__ = EngineDefaults()

    def coupling_value(self) -> int:
        return int(getattr(lib(), self.engine_coupling))

    def validate(self) -> None:
        jacobians = tuple(loop_jacobians())
        if self.loop_jacobian not in jacobians:
            raise ConfigurationError(f"{self.name}: loop_jacobian must be one of {jacobians}, "
                             f"got {self.loop_jacobian!r}")
        if engine_refusal(lambda system: lib().ssx_set_loop_options(
                system, self.tolerance, self.max_iter, self.damping)) is not None:
            raise ConfigurationError(
                f"{self.name}: tolerance > 0, max_iter >= 1 and 0 < damping <= 1 "
                             f"are required (got {self.tolerance}, {self.max_iter}, "
                             f"{self.damping})")
        if isinstance(self.threads, bool) or not isinstance(self.threads, int):
            raise ConfigurationError(
                f"{self.name}: threads must be an integer, got {self.threads!r}")
        refusal = engine_refusal(lambda system: lib().ssx_set_threads(system, self.threads))
        if refusal is not None:
            raise ConfigurationError(f"{self.name}: {refusal}")
        if isinstance(self.input_order, bool) or not isinstance(self.input_order, int):
            raise ConfigurationError(f"{self.name}: input_order must be an integer, got "
                             f"{self.input_order!r}")
        refusal = engine_refusal(lambda system: lib().ssx_set_input_order(system,
                                                                          self.input_order))
        if refusal is not None:
            raise ConfigurationError(f"{self.name}: {refusal}")
        if not isinstance(self.extrapolate_held_inputs, bool):
            raise ConfigurationError(f"{self.name}: extrapolate_held_inputs must be true or "
                                     f"false, got {self.extrapolate_held_inputs!r}")
        if self.step_control is not None:
            if not isinstance(self.step_control, StepControl):
                raise ConfigurationError(f"{self.name}: step_control must be a StepControl or "
                                         f"None, got {self.step_control!r}")
            self.step_control.validate(self.name)


@dataclass
class GaussSeidelAlgorithm(JacobiAlgorithm):
    """Components step in dependency order; a consumer of a direct-feedthrough output gets
    the value of the same communication point (the default). With threads > 1, a run of
    consecutive components none of which feeds a later one of the run steps in parallel."""

    name: str = "Gauss-Seidel"
    engine_coupling: ClassVar[str] = "SSX_GAUSS_SEIDEL"


def default_coupling() -> JacobiAlgorithm:
    """A coupling algorithm of the engine's default ssx_coupling."""
    kinds = {kind.engine_coupling: kind for kind in (JacobiAlgorithm, GaussSeidelAlgorithm)}
    return kinds[ffi.typeof("ssx_coupling").elements[defaults().coupling]]()
