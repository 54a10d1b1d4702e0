"""The seed tutorial and its declarative twin against the exact pendulum."""

from __future__ import annotations

import sys
from pathlib import Path

import hybrid_pendulum
import numpy as np
import pendulum_wall
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipk
from syssimx.system import Statistics

M, L, G, INERTIA, THETA0 = 40.0, 0.6, 9.81, 20.0, 0.5
OMEGA_N = np.sqrt(M * G * L / INERTIA)
# Quarter period of the free pendulum released from rest at THETA0: first wall hit.
EXACT = ellipk(np.sin(THETA0 / 2) ** 2) / OMEGA_N


def free_pendulum(t: float) -> float:
    """theta(t) of the free pendulum released from rest at THETA0 (solve_ivp, rtol 1e-12)."""
    solution = solve_ivp(lambda _, y: [y[1], -OMEGA_N**2 * np.sin(y[0])], (0.0, t),
                         [THETA0, 0.0], rtol=1e-12, atol=1e-14, method="DOP853")
    return float(solution.y[0, -1])


def test_exact_reference_is_the_seed_number():
    assert EXACT == pytest.approx(0.46507759431173046, abs=1e-15)


def test_seed_tutorial_cvode_event_within_1e_8():
    system, pendulum, event_time = hybrid_pendulum.simulate("cvode")
    assert abs(event_time - EXACT) < 1e-8
    # elastic wall: after 2 t* the pendulum starts over from THETA0
    t, data = system.get_history()[pendulum.name]
    assert t[-1] == 1.0
    assert data["theta"][-1] == pytest.approx(free_pendulum(1.0 - 2 * EXACT), abs=1e-6)
    assert np.all(data["theta"] > -1e-8)  # it never passes the wall
    assert t[data["wall_hit"]].tolist() == [event_time]  # the EVENT output, as in SysSimX
    events = system.history.get_all_event_histories()[(pendulum.name, "wall_hit")]
    assert len(events) == 1 and events[0].micro == 0


def test_seed_tutorial_euler_event_within_5e_6():
    _, _, event_time = hybrid_pendulum.simulate("euler")
    # explicit Euler with 1e-4 internal steps: O(h) error of about 2e-6 in the crossing time
    assert abs(event_time - EXACT) < 5e-6


def test_example_writes_the_figure(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                   capsys: pytest.CaptureFixture[str]):
    figure = tmp_path / "pendulum.png"
    monkeypatch.setattr(sys, "argv", ["hybrid_pendulum.py", "--plot", str(figure)])
    hybrid_pendulum.main()
    assert figure.stat().st_size > 10_000
    assert "cvode: wall hit at t = 0.46507759" in capsys.readouterr().out


def test_declarative_plain_component_locates_the_wall_hit():
    system, _ = pendulum_wall.build("cvode")
    result = system.run(0.0, 1.0, 0.05)
    assert [e.event for e in result.events] == ["wall_hit"]
    assert abs(result.events[0].t - EXACT) < 1e-8
    t, data = result["P"]
    assert data["theta"][-1] == pytest.approx(free_pendulum(1.0 - 2 * EXACT), abs=1e-6)
    # grid points plus the event instant recorded before and after handling
    assert np.count_nonzero(np.isclose(t, result.events[0].t, rtol=0, atol=1e-15)) == 2
    assert data["omega"][t > result.events[0].t + 1e-12][0] > 0


def iteration_statistics(method: str) -> Statistics:
    system, _ = pendulum_wall.build("cvode", method)
    system.algorithm.tol_value = 0.0  # stop on the bracket width alone
    return system.run(0.0, 1.0, 0.05).statistics


def test_illinois_needs_few_iterations_bisection_many():
    illinois = iteration_statistics("illinois")
    bisection = iteration_statistics("bisection")
    assert illinois.iterations_per_event[0] <= 10
    # bisection halves 0.05 down to 1e-9: ceil(log2(5e7)) = 26 halvings
    assert bisection.iterations_per_event[0] >= 25
    assert illinois.events == bisection.events == 1
    # no event-free step is repeated: one doStep per grid step plus the localization trials,
    # the rest of the split step, the probe after the event and, when the last trial lands
    # before the zero, the step back to the bracket's far end
    assert illinois.do_step_calls <= 20 + illinois.localization_iterations + 3


def test_initialize_again_reproduces_the_run():
    # the handler's start values apply to the new instance only, not to `parameters`
    system, pendulum = pendulum_wall.build("cvode")
    first = system.run(0.0, 1.0, 0.05)
    theta, event_time = first["P"][1]["theta"].copy(), first.events[0].t
    assert pendulum.parameters["theta0"] == THETA0
    system.initialize(0.0)
    again = system.run(0.0, 1.0, 0.05)
    np.testing.assert_array_equal(again["P"][1]["theta"], theta)
    assert again.events[0].t == event_time
