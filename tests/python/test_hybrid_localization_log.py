"""The localization trials of the seed's pendulum: on the result and in the DEBUG event log."""

from __future__ import annotations

import itertools
import logging
import re

import numpy as np
import pendulum_wall
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipk
from syssimx import SimulationResult

M, L, G, INERTIA, THETA0 = 40.0, 0.6, 9.81, 20.0, 0.5
OMEGA_N = np.sqrt(M * G * L / INERTIA)
EXACT = ellipk(np.sin(THETA0 / 2) ** 2) / OMEGA_N  # first wall hit
TOL_TIME = 1e-9
# CVODE at rtol 1e-10 against solve_ivp at rtol 1e-12: theta good to about 1e-10; 1e-8 leaves
# a margin of a hundred (the same bound the event time is held to).
THETA_TOLERANCE = 1e-8
ITERATION = re.compile(r"^(Illinois|Bisection) iteration (\d+): interval \[([\d.]+), ([\d.]+)\]$")
# the log prints 8 decimals: bounds are off by at most half a unit in the last place
PRINTED = 0.5e-8 + 1e-15


def free_theta(times: list[float]) -> dict[float, float]:
    """theta of the free pendulum released from rest at THETA0 (solve_ivp, rtol 1e-12)."""
    solution = solve_ivp(lambda _, y: [y[1], -OMEGA_N**2 * np.sin(y[0])], (0.0, max(times)),
                         [THETA0, 0.0], t_eval=sorted(times), rtol=1e-12, atol=1e-14,
                         method="DOP853")
    return {float(t): float(theta) for t, theta in zip(solution.t, solution.y[0], strict=True)}


def run_logged(method: str, caplog: pytest.LogCaptureFixture) -> tuple[SimulationResult,
                                                                        list[str]]:
    system, _ = pendulum_wall.build("cvode", method)
    with caplog.at_level(logging.DEBUG, logger="syssimx.hybrid"):
        result = system.run(0.0, 1.0, 0.05)
    lines = [r.getMessage() for r in caplog.records if r.name == "syssimx.hybrid"]
    return result, lines


@pytest.mark.parametrize("method", ["illinois", "bisection"])
def test_trials_on_the_result_follow_the_exact_pendulum(method: str,
                                                       caplog: pytest.LogCaptureFixture):
    result, _ = run_logged(method, caplog)
    [event] = result.events
    assert (event.t_left, event.t_right) == (0.45, 0.5)
    assert len(event.trials) == event.iterations == result.statistics.localization_iterations
    exact = free_theta([0.45, 0.5, *(trial.t for trial in event.trials)])
    assert event.value_left == pytest.approx(exact[0.45], abs=THETA_TOLERANCE)
    assert event.value_right == pytest.approx(exact[0.5], abs=THETA_TOLERANCE)
    a, b = event.t_left, event.t_right
    for trial in event.trials:
        assert trial.value == pytest.approx(exact[trial.t], abs=THETA_TOLERANCE)
        assert a < trial.t < b and a <= trial.a < trial.b <= b
        # the side of the trial is the side of the indicator's sign
        assert (trial.b if trial.value <= 0 else trial.a) == trial.t
        if method == "bisection":
            assert trial.b - trial.a == pytest.approx((b - a) / 2, abs=1e-15)
        a, b = trial.a, trial.b
    assert b == event.t and a < EXACT + THETA_TOLERANCE and EXACT - THETA_TOLERANCE < b
    assert b - a <= TOL_TIME or abs(event.located_value) <= 1e-9  # tol_value of the example
    assert event.located_value <= 0.0


@pytest.mark.parametrize("method", ["illinois", "bisection"])
def test_debug_log_lists_every_iteration(method: str, caplog: pytest.LogCaptureFixture):
    result, lines = run_logged(method, caplog)
    [event] = result.events
    assert f"Indicators at left  (t=0.45000000): {{'P': {{'wall_hit': {event.value_left!r}}}}}" \
        in lines
    assert f"Indicators at right (t=0.50000000): {{'P': {{'wall_hit': {event.value_right!r}}}}}" \
        in lines
    iterations = [m for m in map(ITERATION.match, lines) if m]
    assert len(iterations) == result.statistics.localization_iterations > 0
    assert {m[1] for m in iterations} == {method.capitalize()}
    assert [int(m[2]) for m in iterations] == list(range(1, len(iterations) + 1))
    brackets = [(float(m[3]), float(m[4])) for m in iterations]
    assert brackets[0] == (0.45, 0.5)
    for (a, b), (next_a, next_b) in itertools.pairwise(brackets):
        assert a - PRINTED <= next_a and next_b <= b + PRINTED
        if method == "bisection":
            assert next_b - next_a == pytest.approx((b - a) / 2, abs=2 * PRINTED)
        else:
            assert next_b - next_a < b - a + 2 * PRINTED
    located = lines.index(f"Event located at t={event.t:.8f}")
    assert lines[located - 2] == f"Indicator P.wall_hit = {event.located_value:.4e}"
    assert abs(event.located_value) < THETA_TOLERANCE
    assert lines[located + 1] == "  Events at located time: P.wall_hit"


def test_no_debug_lines_at_info(caplog: pytest.LogCaptureFixture):
    system, _ = pendulum_wall.build("cvode")
    with caplog.at_level(logging.INFO, logger="syssimx.hybrid"):
        system.run(0.0, 1.0, 0.05)
    messages = [r.getMessage() for r in caplog.records if r.name == "syssimx.hybrid"]
    assert "Event crossing in [0.450000, 0.500000]: P.wall_hit" in messages
    assert not any(ITERATION.match(m) for m in messages)
