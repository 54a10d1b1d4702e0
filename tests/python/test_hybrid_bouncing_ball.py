"""Bouncing ball: the FMU falls freely, the master bounces it (restitution 0.8).

Closed form from rest at H0: first impact t1 = sqrt(2 H0 / g) with speed v1 = g t1; the n-th
flight after it lasts 2 e^n v1 / g, so t_n = t1 + (2 v1 / g) sum_{k=1}^{n-1} e^k and the
bounces accumulate at t_inf = t1 (1 + e) / (1 - e) (Zeno).
"""

from __future__ import annotations

import bouncing_ball
import numpy as np
import pytest
from syssimx import SimulationError, System, ZenoError

E, G, H0 = 0.8, 9.81, 1.0
T1 = np.sqrt(2 * H0 / G)
V1 = G * T1
BOUNCES = np.array([T1 + 2 * V1 / G * sum(E**k for k in range(1, n)) for n in range(1, 11)])
T_INF = T1 * (1 + E) / (1 - E)


def ball_system(direction: int) -> System:
    system = bouncing_ball.build(direction=direction, cvode_relative_tolerance=1e-12)
    system.initialize(0.0)
    return system


@pytest.mark.parametrize("direction", [-1, 0])
def test_first_ten_bounces_match_the_closed_form(direction: int):
    system = ball_system(direction)
    result = system.run(0.0, 3.6, 0.01)  # t_10 = 3.579 s, t_11 = 3.676 s
    times = np.array([e.t for e in result.events])
    assert len(times) == 10
    np.testing.assert_allclose(times, BOUNCES, rtol=0, atol=1e-8)
    # with direction 0 the rising ball leaving the floor is not a new event
    assert all(e.event == "floor" and e.micro == 0 for e in result.events)
    _, data = result["Ball"]
    assert data["h"].min() > -1e-8  # never through the floor
    assert max(result.statistics.iterations_per_event) <= 10


def test_zeno_ends_with_the_documented_error_and_keeps_the_history():
    system = ball_system(-1)
    system.algorithm.zeno_min_interval = 1e-4  # flights shorter than 0.1 ms are chattering
    with pytest.raises(ZenoError, match="chattering") as info:
        system.run(0.0, 5.0, 0.01)
    assert info.value.component == "Ball"
    assert info.value.event == "floor"
    # flight n lasts 2 e^n v1 / g < 1e-4 from n = 41 on, just before t_inf
    assert T_INF - 1e-3 < info.value.time < T_INF
    t, data = system.get_history()["Ball"]
    assert t[-1] == pytest.approx(info.value.time, abs=1e-12)
    assert data["h"].min() > -1e-8
    assert len(system.history.get_event_history("Ball", "floor")) == 41


def test_zeno_with_default_options_never_falls_through():
    system = ball_system(-1)
    try:
        system.run(0.0, 5.0, 0.01)
    except SimulationError as exc:
        assert isinstance(exc, ZenoError)
    _, data = system.get_history()["Ball"]
    assert data["h"].min() > -1e-6
