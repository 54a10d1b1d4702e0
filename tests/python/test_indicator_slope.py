"""Localization from the indicator's slope: an indicator on a state whose FMU declares the
state's derivative (a Real's `derivative` attribute) is located from that slope, two trials per
wall hit on the seed's scenario instead of three or four, and the handlers (Python and
declarative) still agree to the bit."""

from __future__ import annotations

import pendulum_wall
import pytest
from syssimx import EventConnection, FMUComponent, HybridAlgorithm, Reinitialize, System, fmus


@pytest.mark.parametrize("stem", ["pendulum_euler", "pendulum_cvode_fmi3"])
def test_the_slope_is_the_declared_derivative(stem: str) -> None:
    pendulum = FMUComponent("P", fmus.path(stem))
    # models/Pendulum: der(theta) (value reference 3) and alpha (2) declare derivative="..."
    # (FMI 2.0: an index into the variables; FMI 3.0: a value reference)
    assert pendulum._indicator_slope("theta") == 3
    assert pendulum._indicator_slope("omega") == 2
    assert pendulum._indicator_slope("alpha") is None


def _seed(solver: str, handler: object, method: str = "illinois") -> tuple[list[float], list[int]]:
    pendulum = FMUComponent("P", fmus.path(f"pendulum_{solver}"))
    pendulum.set_parameters(theta0=0.5, omega0=0.0)
    if solver == "cvode":
        pendulum.set_parameters(cvode_relative_tolerance=1e-10)
    pendulum.add_event_indicator("wall_hit", variable="theta", direction=-1)
    pendulum.add_event_handler("omega_invert", handler)
    system = System("wall")
    system.add_component(pendulum)
    system.add_event_connection(EventConnection("P", "wall_hit", "P", "omega_invert"))
    system.set_algorithm(HybridAlgorithm(tol_time=1e-9, tol_value=1e-9, method=method))
    system.initialize(0.0)
    result = system.run(0.0, 3.0, 0.05)
    pendulum.free()
    return [e.t for e in result.events], [e.iterations for e in result.events]


@pytest.mark.parametrize("solver", ["euler", "cvode"])
def test_two_trials_per_wall_hit_and_the_same_times_from_both_handlers(solver: str) -> None:
    times, iterations = _seed(solver, Reinitialize(theta0="theta", omega0="-omega"))
    python_times, python_iterations = _seed(solver, pendulum_wall.bounce)
    assert len(times) == 3 and iterations == [2, 2, 2]
    assert (python_times, python_iterations) == (times, iterations)
    # bisection to tol_time knows no slope: the same crossings, each within tol_time (the
    # trajectories after the first hit differ by the handling times, below 1e-9 each)
    bisection_times, bisection_iterations = _seed(solver, pendulum_wall.bounce, "bisection")
    assert min(bisection_iterations) > 20
    for k, (t, reference) in enumerate(zip(times, bisection_times, strict=True)):
        assert t == pytest.approx(reference, abs=(k + 1) * 1e-9)
