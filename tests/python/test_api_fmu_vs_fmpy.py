"""A single FMU through a System gives what FMPy's simulate_fmu gives on the same grid."""

from __future__ import annotations

import numpy as np
import pytest
from fmpy import simulate_fmu
from syssimx import FMUComponent, System, fmus, units


@pytest.mark.parametrize("name", ["pendulum_euler", "pendulum_cvode"])
def test_single_fmu_equals_fmpy(name: str):
    path = fmus.path(name)
    start = {"theta0": 1.2, "omega0": -0.3, "L": 0.8}
    reference = simulate_fmu(path, start_time=0.0, stop_time=2.0, output_interval=0.01,
                             start_values=start, output=["theta", "omega", "alpha"])
    pendulum = FMUComponent("P", path)
    pendulum.set_parameters(**start)
    system = System("single")
    system.add_component(pendulum)
    system.initialize(0.0)
    t, values = system.run(0.0, 2.0, 0.01)["P"]
    np.testing.assert_allclose(t, reference["time"], rtol=0, atol=1e-12)
    for port in ("theta", "omega", "alpha"):
        # The same binary stepped on the same grid: equal to rounding.
        np.testing.assert_allclose(values[port], reference[port], rtol=0, atol=1e-12)


def test_outputs_are_quantities_in_the_fmu_units():
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.set_parameters(theta0=units.Quantity(30.0, "degree"))
    assert pendulum.parameters["theta0"] == pytest.approx(np.pi / 6)
    pendulum.initialize(0.0)
    outputs = pendulum.get_outputs()
    assert outputs["theta"].magnitude == pytest.approx(np.pi / 6)
    assert str(outputs["alpha"].units) == "radian / second ** 2"
    assert pendulum.output_specs["alpha"].unit == "rad/s2"
    assert pendulum.input_specs["torque"].unit == "N.m"
    assert units.to_unit("kg.m2") == units.ureg("kg*m**2").units


def test_get_state_holds_outputs_and_parameters():
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.set_parameters(theta0=0.25)
    pendulum.initialize(0.0)
    state = pendulum.get_state()
    assert state["theta"] == {"value": pytest.approx(0.25), "unit": "rad"}
    assert state["m"]["value"] == pytest.approx(40.0)
    assert state["m"]["unit"] == "kg"


def test_unconnected_input_keeps_its_start_value_and_set_inputs_reaches_the_fmu():
    # alpha = -(m g L / I) sin(theta) + torque / I: read torque back through alpha
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.set_parameters(theta0=0.0)
    pendulum.initialize(0.0)
    assert pendulum.get_outputs()["alpha"].magnitude == pytest.approx(0.0, abs=1e-15)
    pendulum.set_inputs({"torque": units.Quantity(2.0, "kN*m")})
    assert pendulum.inputs["torque"].get().magnitude == pytest.approx(2000.0)
    pendulum.do_step(0.0, 1e-3)
    inertia = pendulum.parameters["inertia"]
    alpha = pendulum.get_outputs()["alpha"].magnitude
    theta = pendulum.get_outputs()["theta"].magnitude
    expected = -(40 * 9.81 * 0.6 / inertia) * np.sin(theta) + 2000.0 / inertia
    assert alpha == pytest.approx(expected, rel=1e-12)
