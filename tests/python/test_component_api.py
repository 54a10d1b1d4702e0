"""SysSimX's component API: checkpoint()/restore_checkpoint (ComponentCheckpoint), soft_reset,
reinitialize_instance, get_default_parameters, set_state, component.history, and the
FEMComponent/OpenSimComponent names."""

from __future__ import annotations

import numpy as np
import pytest
from quickstart import Integrator
from syssimx import (
    ComponentCheckpoint,
    ConfigurationError,
    FEMComponent,
    FMUComponent,
    OpenSimComponent,
    fmus,
)
from syssimx.components import FEMComponent as FEMFromComponents


def pendulum() -> FMUComponent:
    """The Euler pendulum: fixed internal steps, so a restored run repeats bit for bit."""
    component = FMUComponent("P", fmus.path("pendulum_euler"))
    component.set_parameters(theta0=0.5)
    return component


def steps(component, t0: float, n: int, dt: float = 0.1) -> list[float]:
    """theta after each of n standalone steps from t0."""
    values = []
    for k in range(n):
        component.do_step(t0 + k * dt, dt)
        values.append(float(component.outputs["theta"].raw()))
    return values


def test_defaults_are_the_declared_values_whatever_was_set():
    component = pendulum()
    defaults = component.get_default_parameters()
    assert defaults["theta0"] == 0.0 and defaults["m"] == 40.0  # Pendulum.mo's starts
    assert component.parameters["theta0"] == 0.5
    defaults["theta0"] = 7.0  # a copy
    assert component.get_default_parameters()["theta0"] == 0.0


def test_checkpoint_restores_an_fmu_exactly():
    component = pendulum()
    component.initialize(0.0)
    steps(component, 0.0, 3)
    checkpoint = component.checkpoint()
    assert isinstance(checkpoint, ComponentCheckpoint)
    assert checkpoint.owner is component and checkpoint.time == pytest.approx(0.3)
    first = steps(component, 0.3, 4)
    component.restore_checkpoint(checkpoint)
    assert component.t == checkpoint.time
    assert component.outputs["theta"].raw() == checkpoint.outputs["theta"]
    assert steps(component, 0.3, 4) == first
    # on its own, the history restarts at the checkpoint
    t, values = component.get_history_arrays()
    np.testing.assert_allclose(t, [0.3, 0.4, 0.5, 0.6, 0.7], rtol=0, atol=1e-12)
    assert list(values["theta"][1:]) == first


def test_checkpoint_of_a_python_component_and_its_errors():
    integrator = Integrator("I", x0=1.0)
    with pytest.raises(ConfigurationError, match=r"I: cannot take a checkpoint: the component "
                       r"does not support rollback"):
        integrator.checkpoint()

    class Rollback(Integrator):
        def snapshot_state(self) -> float:
            return self.x

        def restore_state(self, snapshot: float, t: float) -> None:
            self.x = snapshot

    component = Rollback("R", x0=1.0)
    component.initialize(0.0)
    component.set_inputs({"u": 2.0})
    component.do_step(0.0, 0.5)
    checkpoint = component.checkpoint()
    component.set_inputs({"u": -10.0})
    component.do_step(0.5, 0.5)
    assert component.outputs["y"].raw() == -3.0
    component.restore_checkpoint(checkpoint)
    assert (component.x, component.outputs["y"].raw(), component.inputs["u"].raw()) == \
        (2.0, 2.0, 2.0)
    with pytest.raises(ConfigurationError, match=r"P: the checkpoint belongs to 'R'"):
        pendulum().restore_checkpoint(checkpoint)


def test_soft_reset_starts_again_at_t0():
    component = pendulum()
    component.initialize(0.0)
    first = steps(component, 0.0, 3)
    component.soft_reset(0.0)
    assert component.t == 0.0 and component.outputs["theta"].raw() == 0.5
    assert len(component.history.get_port_history("theta")) == 1
    assert steps(component, 0.0, 3) == first


def test_reinitialize_instance_restarts_from_the_parameters_at_t():
    component = pendulum()
    component.initialize(0.0)
    steps(component, 0.0, 2)
    assert component.outputs["theta"].raw() != 0.5
    component.reinitialize_instance(0.2)
    assert component.t == 0.2 and component.outputs["theta"].raw() == 0.5
    assert component.outputs["omega"].raw() == 0.0


def test_set_state_restarts_from_a_physical_state():
    component = pendulum()
    component.initialize(0.0)
    component.set_state({"theta0": {"value": 0.25, "unit": "rad"}, "omega0": -1.0,
                         "theta": {"value": 9.0, "unit": "rad"}}, 1.0)
    assert component.t == 1.0
    assert (component.outputs["theta"].raw(), component.outputs["omega"].raw()) == (0.25, -1.0)
    assert component.parameters["theta0"] == 0.5  # this start only, as reinitialize
    integrator = Integrator("I", x0=1.0)
    integrator.parameters = {"x0": 1.0}
    integrator.set_state({"u": 3.0}, 0.0)
    assert integrator.inputs["u"].raw() == 3.0


def test_history_is_sysimx_component_history():
    component = pendulum()
    component.initialize(0.0)
    steps(component, 0.0, 2)
    history = component.history
    t, values = history.to_arrays()
    t_ref, values_ref = component.get_history_arrays()
    np.testing.assert_array_equal(t, t_ref)
    np.testing.assert_array_equal(values["theta"], values_ref["theta"])
    theta = history.get_port_history("theta")
    assert theta.unit == "rad" and len(theta) == 3 and "theta" in history and len(history) == 3
    np.testing.assert_allclose(theta.get_values("deg"), np.rad2deg(values_ref["theta"]))
    as_dict = history.to_dict(["omega"], units={"omega": "deg/s"})
    assert as_dict["omega"]["unit"] == "deg/s" and list(as_dict) == ["omega"]
    assert history.mode_switch_events == ()
    with pytest.raises(KeyError, match=r"P: no history for output 'phi'"):
        history.get_port_history("phi")


@pytest.mark.parametrize(("component", "package"),
                         [(FEMComponent, "ngsolve"), (OpenSimComponent, "opensim")])
def test_other_simulators_name_the_package_they_need(component: type, package: str):
    assert FEMFromComponents is FEMComponent
    with pytest.raises(ModuleNotFoundError, match=rf"{component.__name__} needs the "
                       rf"'{package}' package") as caught:
        component("X", "model.file")
    assert caught.value.name == package
