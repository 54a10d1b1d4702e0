"""The pendulum with wall contact: impact times against the exact solution (restitution 1) and
against scipy with event location (restitution 0.5), both at tight tolerances."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipk

STIFFNESS = 40.0 * 9.81 * 0.6 / 20.0
THETA0 = 0.5
CONTACTS = 5
EULER_STEP = 1e-4


def exact_impacts(restitution: float) -> list[float]:
    """Impact k+1 follows impact k after half a period of the swing whose amplitude a has
    sin(a/2) scaled by the restitution at every impact (energy)."""
    w = np.sqrt(STIFFNESS)
    s = np.sin(THETA0 / 2)
    times = [ellipk(s * s) / w]
    for _ in range(CONTACTS - 1):
        s *= restitution
        times.append(times[-1] + 2 * ellipk(s * s) / w)
    return times


def scipy_impacts(restitution: float) -> list[float]:
    def rhs(t: float, x: np.ndarray) -> list[float]:
        return [x[1], -STIFFNESS * np.sin(x[0])]

    def wall(t: float, x: np.ndarray) -> float:
        return x[0]

    wall.terminal = True
    wall.direction = -1
    times, t, x = [], 0.0, [THETA0, 0.0]
    while len(times) < CONTACTS:
        solution = solve_ivp(
            rhs, (t, 10.0), x, events=wall, rtol=1e-12, atol=1e-14, method="DOP853"
        )
        t = solution.t_events[0][0]
        times.append(t)
        x = [0.0, -restitution * solution.y_events[0][0][1]]
    return times


def test_exact_and_scipy_references_agree() -> None:
    assert exact_impacts(0.5) == pytest.approx(scipy_impacts(0.5), abs=1e-9)


def moving_away(fmu) -> bool:
    return fmu.get("omega") > 0.0


def moving_back(fmu) -> bool:
    return fmu.get("omega") < 0.0


@pytest.mark.parametrize("restitution", [1.0, 0.5])
@pytest.mark.parametrize("backend", ["cvode", "euler"])
def test_impact_times(open_fmu, find_time, backend: str, restitution: float) -> None:
    fmu = open_fmu(
        f"pendulum_contact_{backend}",
        starts={"theta0": THETA0, "restitution": restitution, "sense": -1, "theta_wall": 0.0},
        tolerance=1e-10 if backend == "cvode" else None,
    )
    expected = scipy_impacts(restitution) if restitution != 1.0 else exact_impacts(1.0)
    t = 0.0
    for k, t_exact in enumerate(expected):
        impact, t = find_time(fmu, t, 1e-3, 10.0, moving_away)
        # Euler gains energy by (1 + h^2 w^2) per step: its phase error grows like h w^2 t^2
        bound = 1e-8 if backend == "cvode" else EULER_STEP * STIFFNESS * t_exact**2 / 40
        assert impact == pytest.approx(t_exact, abs=bound), f"impact {k + 1}"
        assert fmu.get("contact") == 1.0
        if k + 1 < CONTACTS:
            _, t = find_time(fmu, t, 1e-3, 10.0, moving_back, resolution=1e-6)
