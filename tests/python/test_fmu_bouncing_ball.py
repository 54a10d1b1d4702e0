"""Bouncing ball FMUs against the closed form: t1 = sqrt(2 h0 / g), then flights 2 e^k v1 / g."""

from __future__ import annotations

import math

import pytest

G, E, H0 = 9.81, 0.8, 1.0
EULER_STEP = 1e-4


def closed_form_bounces(count: int) -> list[float]:
    t1 = math.sqrt(2 * H0 / G)
    v1 = G * t1
    times = [t1]
    for k in range(1, count):
        times.append(times[-1] + 2 * E**k * v1 / G)
    return times


def rising(fmu) -> bool:
    return fmu.get("v") > 0.0


def falling(fmu) -> bool:
    return fmu.get("v") < 0.0


@pytest.mark.parametrize("backend", ["cvode", "euler"])
def test_bounce_times(open_fmu, find_time, backend: str) -> None:
    fmu = open_fmu(f"bouncing_ball_{backend}", tolerance=1e-10 if backend == "cvode" else None)
    t = 0.0
    for k, expected in enumerate(closed_form_bounces(5)):
        bounce, t = find_time(fmu, t, 1e-3, 5.0, rising)
        # Euler's height runs ahead by g t h / 2: the first fall lands h/2 late, each later
        # flight about h plus 2 dv / g late (rebound too fast by dv <= k g h): (k+1)^2 h
        bound = 1e-8 if backend == "cvode" else (k + 1) ** 2 * EULER_STEP
        assert bounce == pytest.approx(expected, abs=bound), f"bounce {k + 1}"
        _, t = find_time(fmu, t, 1e-3, 5.0, falling, resolution=1e-6)


def test_ball_comes_to_rest_instead_of_chattering(open_fmu) -> None:
    fmu = open_fmu("bouncing_ball_cvode")
    # the infinitely many ideal bounces end at t1 (1 + 2 e / (1 - e)) = 4.06 s
    for k in range(60):
        fmu.slave.doStep(k * 0.1, 0.1)
    assert (fmu.get("h"), fmu.get("v")) == (0.0, 0.0)


@pytest.mark.parametrize("backend", ["cvode", "euler"])
def test_continuous_ball_bounced_by_reinitialization(open_fmu, backend: str) -> None:
    """The master's bounce: a new instance initialized at t1 with h0 = 0, v0 = -e v."""
    tolerance = 1e-10 if backend == "cvode" else None
    name = f"bouncing_ball_continuous_{backend}"
    t1, t2 = closed_form_bounces(2)
    first = open_fmu(name, tolerance=tolerance)
    first.slave.doStep(0.0, t1)
    v_impact = first.get("v")
    assert v_impact == pytest.approx(-G * t1, rel=1e-12)  # v is linear: both solvers exact
    second = open_fmu(
        name, starts={"h0": 0.0, "v0": -E * v_impact}, tolerance=tolerance, start_time=t1
    )
    second.slave.doStep(t1, t2 - t1)
    # CVODE at rtol 1e-10; Euler's height runs ahead by g t h / 2 = 3.5e-4 m after the flight
    assert second.get("h") == pytest.approx(0.0, abs=1e-9 if backend == "cvode" else 4e-4)
