"""Newton's Jacobian of an algebraic loop from fmi2GetDirectionalDerivative, against finite
differences, on the gain/sum loop with a unit conversion inside it (m -> cm):

    Gain: y = a u [m],  Sum: y = b - c u (u in cm),  u_gain = b / (1 + 100 a c).

Both FMUs declare providesDirectionalDerivative; a Python member has none, so its column of
the Jacobian still comes from finite differences.
"""

from __future__ import annotations

import numpy as np
import pytest
from syssimx import (
    Connection,
    CoSimComponent,
    FMUComponent,
    GaussSeidelAlgorithm,
    JacobiAlgorithm,
    PortSpec,
    PortType,
    System,
    fmus,
)

A, B, C = 1.5, 2.0, 0.02
U_GAIN = B / (1.0 + 100.0 * A * C)  # 0.5 m
TF, DT = 1.0, 0.1
TOLERANCE = 1e-10  # the loop tolerance; the values are of order 1


class PythonSum(CoSimComponent):
    """The Sum FMU's equation in Python: y [m] = b - c u, u in cm."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.input_specs["u"] = PortSpec("u", PortType.REAL, "in", "cm")
        self.output_specs["y"] = PortSpec("y", PortType.REAL, "out", "m")
        self.direct_feedthrough = {"y": {"u"}}

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _value(self) -> float:
        return B - C * self.inputs["u"].raw()

    def _update_output_states(self, t=None, event_names=None) -> None:
        self.outputs["y"].set(self._value(), t)

    def evaluate_outputs(self, inputs, t=None):
        for name, value in inputs.items():
            self.inputs[name].set(value, t)
        return {"y": self._value()}


def gain_sum_loop(algorithm: JacobiAlgorithm, python_sum: bool = False) -> System:
    gain = FMUComponent("Gain", fmus.path("gain"))
    gain.set_parameters(k=A)
    if python_sum:
        summer: CoSimComponent = PythonSum("Sum")
    else:
        summer = FMUComponent("Sum", fmus.path("sum"))
        summer.set_parameters(b=B, c=C)
    system = System("gain-sum loop")
    system.add_component(gain)
    system.add_component(summer)
    system.add_connection(Connection("Gain", "y", "Sum", "u"))
    system.add_connection(Connection("Sum", "y", "Gain", "u"))
    system.set_algorithm(algorithm)
    return system


def solved(system: System):
    system.initialize(0.0)
    result = system.run(0.0, TF, DT)
    np.testing.assert_allclose(result["Gain"][1]["y"], A * U_GAIN, rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(result["Sum"][1]["y"], U_GAIN, rtol=0, atol=TOLERANCE)
    return result.statistics


def test_the_blocks_declare_directional_derivatives():
    for name in ("gain", "sum"):
        description = FMUComponent(name, fmus.path(name)).info.description
        assert description.coSimulation.providesDirectionalDerivative


@pytest.mark.parametrize("coupling", [GaussSeidelAlgorithm, JacobiAlgorithm])
def test_directional_derivatives_solve_the_loop_like_finite_differences(coupling):
    analytic_system = gain_sum_loop(coupling())
    analytic = solved(analytic_system)
    numeric = solved(gain_sum_loop(coupling(loop_jacobian="finite_differences")))

    # two unknowns (Gain.u, Sum.u): one directional derivative per column per Newton iteration
    assert analytic.loop_iterations >= 1
    assert analytic.directional_derivatives == 2 * analytic.loop_iterations
    assert analytic.loop_iterations <= numeric.loop_iterations
    assert numeric.directional_derivatives == 0
    counters = analytic_system.components["Gain"].instance.counters()
    assert counters["directional_derivative"] == analytic.loop_iterations


def test_a_python_member_keeps_finite_differences_for_its_column():
    statistics = solved(gain_sum_loop(GaussSeidelAlgorithm(), python_sum=True))
    # only the Gain's input column comes from its FMU
    assert statistics.directional_derivatives == statistics.loop_iterations >= 1


def test_an_unknown_jacobian_mode_is_refused():
    with pytest.raises(ValueError, match="loop_jacobian"):
        gain_sum_loop(GaussSeidelAlgorithm(loop_jacobian="exact")).initialize(0.0)
