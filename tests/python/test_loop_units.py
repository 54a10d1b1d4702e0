"""An algebraic loop of two FMUs with a unit conversion inside it, against its closed form.

    Gain: y = a u        u, y in m
    Sum:  y = b - c u    u in cm, y in m (c in m per cm)

    Gain.y [m] -> Sum.u [cm] (the connection scales by 100), Sum.y [m] -> Gain.u [m]

Going once around the loop: u_gain = b - c * 100 * a * u_gain, so u_gain = b / (1 + 100 a c).
"""

from __future__ import annotations

import numpy as np
from syssimx import Connection, FMUComponent, GaussSeidelAlgorithm, System, fmus

# The loop gain 100 a c = 3: the loop equation is well conditioned (1 + 3), but a plain
# fixed-point pass u <- b - 3 u diverges, so matching the closed form needs a real solve.
A, B, C = 1.5, 2.0, 0.02
U_GAIN = B / (1.0 + 100.0 * A * C)  # 0.5 m
TF, DT = 1.0, 0.1
TOLERANCE = 1e-10  # the requirement; the values are of order 1, rounding is 1e-16


def gain_sum_loop() -> System:
    gain = FMUComponent("Gain", fmus.path("gain"))
    gain.set_parameters(k=A)
    summer = FMUComponent("Sum", fmus.path("sum"))
    summer.set_parameters(b=B, c=C)
    system = System("gain-sum loop in m and cm")
    system.add_component(gain)
    system.add_component(summer)
    system.add_connection(Connection("Gain", "y", "Sum", "u"))
    system.add_connection(Connection("Sum", "y", "Gain", "u"))
    system.set_algorithm(GaussSeidelAlgorithm())
    return system


def test_the_fmus_declare_the_units_of_the_loop():
    system = gain_sum_loop()
    gain, summer = system.components["Gain"], system.components["Sum"]
    assert (gain.input_specs["u"].unit, gain.output_specs["y"].unit) == ("m", "m")
    assert (summer.input_specs["u"].unit, summer.output_specs["y"].unit) == ("cm", "m")


def test_loop_with_a_unit_conversion_matches_the_closed_form_at_every_sample():
    system = gain_sum_loop()
    system.initialize(0.0)
    result = system.run(0.0, TF, DT)
    t, gain = result["Gain"]
    summer = result["Sum"][1]
    assert len(t) == round(TF / DT) + 1

    np.testing.assert_allclose(gain["y"], A * U_GAIN, rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(summer["y"], U_GAIN, rtol=0, atol=TOLERANCE)
    # Sum sees the gain's metres as centimetres: y = b - c * 100 * (a u_gain)
    np.testing.assert_allclose(B - C * 100.0 * gain["y"], summer["y"], rtol=0, atol=TOLERANCE)

    # Solved at initialization and at every communication point after it. The start values (0)
    # are far from the solution, so the first solve iterates: Newton on this linear loop needs
    # one step (the finite-difference Jacobian is exact up to rounding), perhaps one more to
    # confirm. Later solves start from the previous solution, which already satisfies the loop.
    stats = result.statistics
    assert stats.loop_solves == len(t)
    assert 1 <= stats.loop_iterations <= 3
