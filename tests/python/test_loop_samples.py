"""Every recorded sample of an algebraic loop satisfies the loop equations at its own time.

A PI controller (u = kp (0 - m) + ki I, I' = -m) measures a gain's output (y = k u) that it
drives itself: an algebraic loop of two FMUs whose solution decays with the integral I. The
engine solves the loop at the end of each macro step, so at every sample

    Gain.y = k PI.u    and    PI.u = ki I / (1 + kp k).

With the loop input held over a step, the integral moves exactly by -h y_n (the controller's
Euler back-end integrates a constant error exactly), so the samples follow the recursion
I_{n+1} = I_n - h k u_n, an independent reference of the whole trajectory.
"""

from __future__ import annotations

import numpy as np
import pytest
from syssimx import Connection, FMUComponent, GaussSeidelAlgorithm, JacobiAlgorithm, System, fmus

KP, KI, K, INTEGRAL0 = 0.5, 1.0, 0.5, 1.0
TF, DT = 2.0, 0.1
TOLERANCE = 1e-10  # the loop tolerance of the algorithms; values are of order 1


def controlled_gain(algorithm: JacobiAlgorithm) -> System:
    controller = FMUComponent("PI", fmus.path("pi_controller"))
    controller.set_parameters(kp=KP, ki=KI, integral0=INTEGRAL0)
    gain = FMUComponent("Gain", fmus.path("gain"))
    gain.set_parameters(k=K)
    system = System("PI and gain loop")
    system.add_component(controller)
    system.add_component(gain)
    system.add_connection(Connection("PI", "u", "Gain", "u"))
    system.add_connection(Connection("Gain", "y", "PI", "measurement"))
    system.set_algorithm(algorithm)
    return system


def sampled_reference(n_samples: int) -> np.ndarray:
    control = np.empty(n_samples)
    integral = INTEGRAL0
    for n in range(n_samples):
        control[n] = KI * integral / (1.0 + KP * K)
        integral -= DT * K * control[n]
    return control


@pytest.mark.parametrize("algorithm", [GaussSeidelAlgorithm(), JacobiAlgorithm()],
                         ids=["gauss-seidel", "jacobi"])
def test_every_sample_satisfies_the_loop_equations(algorithm: JacobiAlgorithm):
    system = controlled_gain(algorithm)
    system.initialize(0.0)
    result = system.run(0.0, TF, DT)
    t, controller = result["PI"]
    gain = result["Gain"][1]
    assert len(t) == round(TF / DT) + 1

    np.testing.assert_allclose(gain["y"], K * controller["u"], rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(controller["u"], sampled_reference(len(t)), rtol=0,
                               atol=TOLERANCE)
    # one solve at t0 and one per step, none twice
    assert result.statistics.loop_solves == len(t)
