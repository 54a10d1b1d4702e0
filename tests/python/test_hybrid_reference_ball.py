"""Events on the Reference FMUs' BouncingBall (FMI 2.0), a third-party FMU with a fixed
internal step of 1 ms: its outputs are piecewise constant in the master's time, and its
velocity comes to rest at exactly 0.0 (from t = 2.6 s on with its default parameters).
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from syssimx import FMUComponent, HybridAlgorithm, System


def reference_fmu(name: str) -> Path:
    """A Reference FMU (FMI 2.0) from SYSSIMX_REFERENCE_FMUS or ../shared/reference-fmus."""
    root = Path(__file__).resolve().parents[2]
    folder = Path(os.environ.get("SYSSIMX_REFERENCE_FMUS",
                                 root.parent / "shared" / "reference-fmus"))
    path = folder / "fmi2" / f"{name}.fmu"
    if not path.is_file():
        pytest.skip(f"the Reference FMUs are not there ({path} is missing; set "
                    "SYSSIMX_REFERENCE_FMUS to the folder holding fmi2/)")
    return path


def ball_events(direction: int, method: str = "illinois") -> tuple[list, float]:
    """The events of an indicator on v up to 3 s (dt 0.01), and when v came to rest."""
    ball = FMUComponent("B", str(reference_fmu("BouncingBall")))
    ball.add_event_indicator("v_zero", variable="v", direction=direction)
    system = System("reference ball")
    system.add_component(ball)
    system.set_algorithm(HybridAlgorithm(method=method))
    system.initialize(0.0)
    result = system.run(0.0, 3.0, 0.01)
    t, data = result["B"]
    moving = [time for time, v in zip(t, data["v"], strict=True) if v != 0.0]
    return result.events, max(moving)


@pytest.mark.parametrize(("direction", "at_rest"), [(-1, 0), (1, 1), (0, 1)])
def test_velocity_at_rest_fires_at_most_once(direction: int, at_rest: int):
    events, last_moving = ball_events(direction)
    assert 2.5 < last_moving < 2.7
    resting = [e for e in events if e.t > last_moving]
    assert len(resting) == at_rest
    # the ball falls from rest at t0 (v starts on zero and goes negative: a falling crossing
    # at t0), then crosses zero at every apex (falling) and bounce (rising): 11 of each
    falling = 1 + 11 if direction in (-1, 0) else 0
    rising = 11 if direction in (1, 0) else 0
    assert len(events) == falling + rising + at_rest


def test_default_localization_stays_within_two_iterations_of_bisection():
    events, _ = ball_events(0)
    halving, _ = ball_events(0, "bisection")
    assert [round(e.t, 6) for e in events] == [round(e.t, 6) for e in halving]
    for event, bisected in zip(events, halving, strict=True):
        assert event.iterations <= bisected.iterations + 2
    # Illinois alone creeps along the flat pieces
    unguarded, _ = ball_events(0, "illinois_unguarded")
    assert max(e.iterations for e in unguarded) > max(b.iterations for b in halving) + 10
