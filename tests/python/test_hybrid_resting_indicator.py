"""Indicators that reach zero and rest there, or only touch it: one crossing each.

The rule: reaching zero from one side is the crossing (falling from above, rising from below);
an indicator that crossed onto zero makes no new crossing while it stays there or when it
leaves, whichever side it leaves to.
"""

from __future__ import annotations

from collections.abc import Callable

import pytest
from syssimx import EventConnection, FMUComponent, System, fmus
from test_hybrid_events import Clock

MU, G, V0 = 0.3, 9.81, 2.0
STOP = V0 / (MU * G)  # the sliding mass stops here, v exactly 0 from then on
TOL_TIME = 1e-9


def sliding_mass(direction: int) -> System:
    mass = FMUComponent("M", fmus.path("sliding_mass"))
    mass.set_parameters(mu=MU, g=G, v0=V0)
    mass.add_event_indicator("stopped", variable="v", direction=direction)
    system = System("sliding mass")
    system.add_component(mass)
    system.initialize(0.0)
    system.algorithm.tol_time = TOL_TIME
    return system


@pytest.mark.parametrize(("direction", "events"), [(-1, 1), (1, 0), (0, 1)])
def test_velocity_resting_on_zero_fires_once_at_the_stop(direction: int, events: int):
    system = sliding_mass(direction)
    result = system.run(0.0, 3.0, 0.05)  # 47 macro steps with v exactly 0 after the stop
    assert len(result.events) == events
    for event in result.events:
        assert event.event == "stopped" and event.micro == 0
        # the event is the far end of a bracket of tol_time around the stop
        assert STOP <= event.t <= STOP + TOL_TIME + 1e-12
        assert event.located_value == 0.0
    _, data = result["M"]
    assert data["v"][-1] == 0.0



def clock_events(indicator: Callable[[float], float], direction: int) -> list[float]:
    clock = Clock()
    clock.add_event_indicator("z", func=lambda c: indicator(c.x), direction=direction)
    clock.add_event_handler("seen", lambda comp, names, t: None)
    system = System("clock")
    system.add_component(clock)
    system.add_event_connection(EventConnection("C", "z", "C", "seen"))
    system.initialize(0.0)
    system.algorithm.tol_time = TOL_TIME
    return [e.t for e in system.run(0.0, 1.0, 0.1).events]


def touch(x: float) -> float:
    """Falls onto zero at x = 0.35 (between grid points), rests there until 0.62, goes back up."""
    return 0.35 - x if x < 0.35 else (0.0 if x < 0.62 else x - 0.62)


def plateau_then_below(x: float) -> float:
    """Falls onto zero at 0.35, rests there until 0.62, then goes below zero."""
    return 0.35 - x if x < 0.35 else (0.0 if x < 0.62 else 0.62 - x)


def plateau_then_back(x: float) -> float:
    """Rises onto zero at 0.35, rests there until 0.62, then goes back below zero."""
    return x - 0.35 if x < 0.35 else (0.0 if x < 0.62 else 0.62 - x)


@pytest.mark.parametrize(("indicator", "direction", "crossing"), [
    (touch, -1, True), (touch, 0, True), (touch, 1, False),
    (plateau_then_below, -1, True), (plateau_then_below, 0, True), (plateau_then_below, 1, False),
    (plateau_then_back, 1, True), (plateau_then_back, 0, True), (plateau_then_back, -1, False),
])
def test_reaching_zero_is_the_one_crossing(indicator: Callable[[float], float], direction: int,
                                            crossing: bool):
    times = clock_events(indicator, direction)
    if crossing:
        assert len(times) == 1
        assert 0.35 <= times[0] <= 0.35 + TOL_TIME + 1e-12
    else:
        assert times == []


def test_a_real_crossing_after_a_rest_fires_again():
    # rests on zero from 0.35 to 0.62, leaves upwards, then falls through zero at 0.8
    def z(x: float) -> float:
        if x < 0.35:
            return 0.35 - x
        return 0.0 if x < 0.62 else (x - 0.62 if x < 0.71 else 0.8 - x)

    times = clock_events(z, -1)
    assert len(times) == 2
    assert times[0] == pytest.approx(0.35, abs=2 * TOL_TIME)
    assert times[1] == pytest.approx(0.8, abs=2 * TOL_TIME)
