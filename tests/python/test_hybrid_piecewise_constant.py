"""Localization on a piecewise-constant indicator: a cosine sampled and held every millisecond.

The held output y(t) = cos(2 pi f t_k), t_k the last sample instant, falls through zero at the
first sample at or after the cosine's zero 1/(4f); between samples it is flat, which defeats
regula falsi. The default method must stay within two iterations of bisection there and keep its
few iterations on smooth indicators (the seed pendulum, test_hybrid_pendulum.py).
"""

from __future__ import annotations

import math

import pytest
from syssimx import FMUComponent, HybridAlgorithm, System, fmus

F, HOLD = 0.7, 1e-3
ZEROS = [(2 * k + 1) / (4 * F) for k in range(3)]  # the cosine's zeros up to 2 s
# the held output reaches them at the next sample instant
HELD_ZEROS = [math.ceil(z / HOLD) * HOLD for z in ZEROS]


def held_cosine_events(method: str, tol_time: float) -> list:
    hold = FMUComponent("H", fmus.path("sample_hold"))
    hold.set_parameters(f=F, hold_step=HOLD)
    hold.add_event_indicator("through_zero", variable="y", direction=0)
    system = System("sample and hold")
    system.add_component(hold)
    system.set_algorithm(HybridAlgorithm(tol_time=tol_time, method=method))
    system.initialize(0.0)
    return system.run(0.0, 2.0, 0.05).events


@pytest.mark.parametrize("tol_time", [1e-9, 1e-6])
def test_default_method_needs_at_most_two_iterations_more_than_bisection(tol_time: float):
    events = held_cosine_events("illinois", tol_time)
    bisection = held_cosine_events("bisection", tol_time)
    assert len(events) == len(bisection) == 3
    for event, halving in zip(events, bisection, strict=True):
        assert event.iterations <= halving.iterations + 2


@pytest.mark.parametrize("method", ["illinois", "bisection", "illinois_unguarded"])
@pytest.mark.parametrize("tol_time", [1e-9, 1e-6])
def test_event_is_the_sample_instant_after_the_cosine_zero(method: str, tol_time: float):
    events = held_cosine_events(method, tol_time)
    assert [e.t for e in events] == pytest.approx(HELD_ZEROS, abs=tol_time)
    for event, zero, held in zip(events, ZEROS, HELD_ZEROS, strict=True):
        assert 0.0 <= held - zero < HOLD
        assert held - 1e-12 <= event.t  # the far side of the jump


def test_methods_are_the_engine_locators():
    with pytest.raises(ValueError, match=r"one of \('illinois', 'bisection', "
                                         r"'illinois_unguarded'\), got 'brent'"):
        HybridAlgorithm(method="brent").validate()
