"""Localization from the indicator's slope: an indicator on a state whose FMU declares the
state's derivative (a Real's `derivative` attribute) is located from that slope, two trials per
wall hit on the seed's scenario instead of three or four, the second stepping on from the
first, and the handlers (Python and declarative) still agree to the bit."""

from __future__ import annotations

import pendulum_wall
import pytest
from syssimx import FMUComponent, Reinitialize, fmus


@pytest.mark.parametrize("stem", ["pendulum_euler", "pendulum_cvode_fmi3"])
def test_the_slope_is_the_declared_derivative(stem: str) -> None:
    pendulum = FMUComponent("P", fmus.path(stem))
    # models/Pendulum: der(theta) (value reference 3) and alpha (2) declare derivative="..."
    # (FMI 2.0: an index into the variables; FMI 3.0: a value reference)
    assert pendulum._indicator_slope("theta") == 3
    assert pendulum._indicator_slope("omega") == 2
    assert pendulum._indicator_slope("alpha") is None


def _seed(solver: str, handler: object, method: str = "illinois") -> tuple[list[float], list[int]]:
    system, pendulum = pendulum_wall.build(solver, method, handler)
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


@pytest.mark.parametrize("solver", ["euler", "cvode"])
def test_the_second_trial_steps_on_from_the_first(solver: str) -> None:
    """The first trial lands short of the crossing and the system stays there: the second
    steps on from it. Per wall hit: one restore of the macro step's start and one after the
    probe; doSteps: the step that crossed, the two trials and the probe."""
    system, pendulum = pendulum_wall.build(solver, "illinois",
                                           Reinitialize(theta0="theta", omega0="-omega"))
    result = system.run(0.0, 30.0, 0.05)
    pendulum.free()
    assert len(result.events) == 32
    for k, event in enumerate(result.events):
        short, across = event.trials
        assert short.a == short.t < across.t == event.t
        assert across.a == short.t and across.value < 0.0 < short.value
        assert (event.rollbacks, event.do_steps) == (2, 4)
        if solver == "cvode":  # the odd multiples of the quarter period (Euler drifts)
            assert event.t == pytest.approx((2 * k + 1) * pendulum_wall.QUARTER_PERIOD,
                                            abs=2e-8)
