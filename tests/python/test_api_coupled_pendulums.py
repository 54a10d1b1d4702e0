"""Two pendulums coupled by the torsion spring FMU, against the monolithic system.

Co-simulation holds each coupling input constant over a macro step, so both Jacobi and
Gauss-Seidel are first-order in dt: halving dt halves the error.
"""

from __future__ import annotations

import coupled_pendulums  # the system: two pendulum FMUs and the torsion spring FMU
import numpy as np
import pytest
from scipy.integrate import solve_ivp
from syssimx import GaussSeidelAlgorithm, JacobiAlgorithm

M, L, G, INERTIA = 40.0, 0.6, 9.81, 20.0
K, D, TF = coupled_pendulums.K, coupled_pendulums.D, coupled_pendulums.TF  # spring, horizon
DTS = (0.04, 0.02, 0.01)


def monolithic(t_eval: np.ndarray) -> np.ndarray:
    def rhs(_: float, y: np.ndarray) -> list[float]:
        th1, om1, th2, om2 = y
        tau1 = -K * (th1 - th2) - D * (om1 - om2)
        return [om1, (-M * G * L * np.sin(th1) + tau1) / INERTIA,
                om2, (-M * G * L * np.sin(th2) - tau1) / INERTIA]

    solution = solve_ivp(rhs, (0.0, TF), [0.5, 0.0, 0.0, 0.0], t_eval=t_eval, rtol=1e-12,
                         atol=1e-14, method="DOP853")
    return solution.y[[0, 2]]


def max_error(algorithm: JacobiAlgorithm, dt: float) -> float:
    system = coupled_pendulums.build(algorithm)
    system.initialize(0.0)
    result = system.run(0.0, TF, dt)
    t, p1 = result["P1"]
    _, p2 = result["P2"]
    reference = monolithic(t)
    return float(max(np.max(np.abs(p1["theta"] - reference[0])),
                     np.max(np.abs(p2["theta"] - reference[1]))))


@pytest.mark.parametrize("algorithm", [JacobiAlgorithm, GaussSeidelAlgorithm])
def test_error_shrinks_linearly_with_dt(algorithm: type[JacobiAlgorithm]):
    errors = [max_error(algorithm(), dt) for dt in DTS]
    ratios = [errors[i] / errors[i + 1] for i in range(len(errors) - 1)]
    # first order: each halving of dt halves the error (1.6..2.4 leaves room for the
    # higher-order terms at the coarsest step)
    assert all(1.6 < r < 2.4 for r in ratios), (errors, ratios)
    assert errors[-1] < 0.05


def test_gauss_seidel_is_not_worse_than_jacobi():
    assert max_error(GaussSeidelAlgorithm(), 0.01) <= max_error(JacobiAlgorithm(), 0.01) * 1.01


def test_spring_sees_the_pendulum_angles():
    system = coupled_pendulums.build(GaussSeidelAlgorithm())
    system.initialize(0.0)
    result = system.run(0.0, 0.1, 0.01)
    _, spring = result["Spring"]
    # at t0 the spring twists by 0.5 rad and nothing moves yet: tau1 = -K * 0.5
    assert spring["tau1"][0] == pytest.approx(-K * 0.5, rel=1e-12)
    np.testing.assert_allclose(spring["tau2"], -spring["tau1"], rtol=0, atol=1e-12)
