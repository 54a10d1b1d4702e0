"""FMU failures: mid-run errors and the instance proxy's status checks."""

from __future__ import annotations

import numpy as np
import pytest
from fixture_fmus import fmu_path
from syssimx import Connection, FMUComponent, FMUError, SimulationError, System, fmus


def failing_system(fail_time: float) -> System:
    failing = FMUComponent("Bad", fmu_path("failing"))
    failing.set_parameters(fail_time=fail_time)
    system = System("S")
    system.add_component(failing)
    return system


def test_fmu_error_mid_run_names_component_time_status_and_message():
    system = failing_system(0.35)
    system.initialize(0.0)
    with pytest.raises(SimulationError) as info:
        system.run(0.0, 1.0, 0.1)
    error = info.value
    assert error.component == "Bad"
    assert error.time == pytest.approx(0.3)  # the step from 0.3 to 0.4 passes fail_time
    assert error.status == 3  # fmi2Error
    assert "fail_time" in error.fmu_message
    assert "Bad" in str(error) and "fmi2Error" in str(error) and "fail_time" in str(error)
    t, data = system.get_history()["Bad"]
    np.testing.assert_allclose(t, [0.0, 0.1, 0.2, 0.3], atol=1e-12)
    assert data["y"].shape == (4,)


def test_failure_inside_a_coupled_system_names_the_failing_component():
    system = failing_system(0.17)
    copy = FMUComponent("Copy", fmu_path("failing"))
    system.add_component(copy)
    system.add_connection(Connection("Copy", "y", "Bad", "u"))
    system.initialize(0.0)
    with pytest.raises(SimulationError, match="'Bad'") as info:
        system.run(0.0, 1.0, 0.05)
    assert info.value.component == "Bad"
    assert info.value.time == pytest.approx(0.15)


def test_proxy_raises_with_the_fmu_message_above_warning():
    failing = FMUComponent("Bad", fmu_path("failing"))
    failing.set_parameters(fail_time=0.0)
    failing.initialize(0.0)
    with pytest.raises(FMUError, match=r"fmi2DoStep returned Error: .*fail_time") as info:
        failing.instance.doStep(0.0, 0.1)
    assert info.value.status == 3
    assert info.value.component == "Bad"


def test_fmu_state_round_trip_through_the_proxy():
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.set_parameters(theta0=0.5)
    pendulum.initialize(0.0)
    instance = pendulum.instance
    vr = [pendulum.value_reference("theta")]
    state = instance.getFMUstate()
    serialized = instance.serializeFMUstate(state)
    instance.doStep(0.0, 0.1)
    moved = instance.getReal(vr)[0]
    instance.setFMUstate(state)
    assert instance.getReal(vr)[0] == 0.5
    instance.doStep(0.0, 0.1)
    assert instance.getReal(vr)[0] == moved  # same state, same step, same number
    restored = instance.deserializeFMUState(serialized)
    instance.setFMUState(restored)
    assert instance.getReal(vr)[0] == 0.5
    instance.freeFMUState(restored)
    instance.freeFMUstate(state)


def test_state_of_a_replaced_instance_is_refused():
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.initialize(0.0)
    state = pendulum.instance.getFMUstate()
    pendulum.instance.freeInstance()
    pendulum.reinitialize(0.0, theta0=0.1)
    with pytest.raises(FMUError, match="freed or replaced"):
        pendulum.instance.setFMUstate(state)
    assert pendulum.get_outputs()["theta"].magnitude == pytest.approx(0.1)


def test_state_survives_the_reset_of_reinitialize():
    """reinitialize resets the live instance (fmi2Reset): FMI keeps its FMU states valid."""
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.set_parameters(theta0=0.5)
    pendulum.initialize(0.0)
    state = pendulum.instance.getFMUstate()
    pendulum.reinitialize(0.0, theta0=0.1)
    assert pendulum.instance.counters()["instantiate"] == 1
    assert pendulum.get_outputs()["theta"].magnitude == 0.1
    pendulum.instance.setFMUstate(state)
    theta = pendulum.value_reference("theta")
    assert pendulum.instance.getReal([theta])[0] == 0.5
    pendulum.instance.freeFMUstate(state)
