"""The pendulum FMUs against scipy (solve_ivp at rtol 1e-12) and the exact quarter period."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipk

M, L, G, INERTIA = 40.0, 0.6, 9.81, 20.0
STIFFNESS = M * G * L / INERTIA
THETA0 = 0.5
EXACT_QUARTER_PERIOD = 0.46507759431173046


def reference(torque: float, times: np.ndarray) -> np.ndarray:
    def rhs(t: float, x: np.ndarray) -> list[float]:
        return [x[1], -STIFFNESS * np.sin(x[0]) + torque / INERTIA]

    solution = solve_ivp(
        rhs, (0.0, times[-1]), [THETA0, 0.0], t_eval=times, rtol=1e-12, atol=1e-14, method="DOP853"
    )
    return solution.y


def test_exact_quarter_period_is_the_elliptic_integral() -> None:
    quarter = ellipk(np.sin(THETA0 / 2) ** 2) / np.sqrt(STIFFNESS)
    assert quarter == pytest.approx(EXACT_QUARTER_PERIOD, abs=1e-15)


@pytest.mark.parametrize("torque", [0.0, 5.0])
def test_cvode_follows_scipy_for_three_seconds(open_fmu, torque: float) -> None:
    fmu = open_fmu("pendulum_cvode", starts={"theta0": THETA0, "torque": torque}, tolerance=1e-10)
    dt = 0.01
    times = np.arange(1, 301) * dt
    theta = []
    for k, _ in enumerate(times):
        fmu.slave.doStep(k * dt, dt)
        theta.append(fmu.get("theta"))
    expected = reference(torque, times)
    # BDF's global error stays within some tens of its local tolerance 1e-10
    assert np.max(np.abs(np.array(theta) - expected[0])) < 1e-8


def falling_through_zero(fmu) -> bool:
    return fmu.get("theta") <= 0.0


@pytest.mark.parametrize(
    ("name", "tolerance", "bound"),
    [
        ("pendulum_cvode", 1e-10, 1e-8),
        # explicit Euler at h = 1e-4 is first order: late by about 2e-6 s (as in the seed)
        ("pendulum_euler", None, 5e-6),
    ],
)
def test_first_zero_crossing_is_the_quarter_period(
    open_fmu, find_time, name: str, tolerance: float | None, bound: float
) -> None:
    fmu = open_fmu(name, starts={"theta0": THETA0}, tolerance=tolerance)
    dt = 1e-3 if name.endswith("cvode") else 1e-4
    crossing, _ = find_time(fmu, 0.0, dt, 1.0, falling_through_zero)
    assert crossing == pytest.approx(EXACT_QUARTER_PERIOD, abs=bound)


def test_euler_reproduces_the_seed_event_time(open_fmu, find_time) -> None:
    fmu = open_fmu("pendulum_euler", starts={"theta0": THETA0})
    crossing, _ = find_time(fmu, 0.0, 1e-4, 1.0, falling_through_zero)
    # the seed printed 0.46507956 (8 digits) for plain explicit Euler at h = 1e-4
    assert crossing == pytest.approx(0.46507956, abs=5e-9)


def test_alpha_follows_a_new_torque_without_a_step(open_fmu) -> None:
    fmu = open_fmu("pendulum_euler", starts={"theta0": THETA0})
    fmu.slave.doStep(0.0, 0.1)
    theta = fmu.get("theta")
    fmu.set("torque", -3.0)
    assert fmu.get("alpha") == pytest.approx(-STIFFNESS * np.sin(theta) - 3.0 / INERTIA, abs=1e-15)
