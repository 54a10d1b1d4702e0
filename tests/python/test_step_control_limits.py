"""The step control's limits (issue 35, item 4): no step is shorter than min_step, and a step
at min_step whose coupling error still exceeds the tolerance is counted
(statistics.steps_over_tolerance) and warned of once, or stops the run with strict=True. Before,
such steps were accepted without a word (largest_error far above 1)."""

from __future__ import annotations

import warnings

import pytest
from syssimx import Connection, FMUComponent, GaussSeidelAlgorithm, StepControl, System, fmus
from syssimx.errors import ConfigurationError, SimulationError, SysSimXWarning


def pendulum_and_spring(control: StepControl) -> System:
    system = System("pendulum and spring")
    pendulum = FMUComponent("P", fmus.path("pendulum_cvode"))
    pendulum.set_parameters(theta0=0.5)
    system.add_component(pendulum)
    system.add_component(FMUComponent("Spring", fmus.path("torsion_spring")))
    system.add_connection(Connection("P", "theta", "Spring", "theta1"))
    system.add_connection(Connection("P", "omega", "Spring", "omega1"))
    system.add_connection(Connection("Spring", "tau1", "P", "torque"))
    system.set_algorithm(GaussSeidelAlgorithm(input_order=1, step_control=control))
    return system


@pytest.mark.parametrize("rollback", [True, False])
def test_steps_at_min_step_over_the_tolerance_are_counted_and_warned_once(rollback: bool):
    # a tolerance no step of 0.01 can meet
    system = pendulum_and_spring(StepControl(rtol=1e-12, atol=1e-12, min_step=0.01,
                                             rollback=rollback))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        system.initialize(0.0)
        result = system.run(0.0, 1.0, 0.1)
    statistics = result.statistics
    # before, with rollback a rejected step shortened to min_step left a sliver before the
    # grid point: a step of 1.4e-17 from t = 0.09999999999999999, which CVODE refused
    assert statistics.smallest_step >= 0.01 * (1 - 1e-12)
    # where the rest of an interval is under two min_steps it is one step (no sliver after it)
    assert statistics.largest_step < 0.02 * (1 + 1e-9)
    assert statistics.largest_error > 1.0
    assert statistics.steps_over_tolerance == statistics.accepted_steps >= 90
    about = [str(w.message) for w in caught
             if issubclass(w.category, SysSimXWarning) and "min_step" in str(w.message)]
    assert len(about) == 1
    assert f"{statistics.accepted_steps} communication step(s)" in about[0]


def test_a_strict_step_control_stops_at_the_first_such_step():
    system = pendulum_and_spring(StepControl(rtol=1e-12, atol=1e-12, min_step=0.01,
                                             strict=True))
    system.initialize(0.0)
    with pytest.raises(SimulationError) as caught:
        system.run(0.0, 1.0, 0.1)
    message = str(caught.value)
    assert "min_step=0.01" in message and "strict step control" in message
    assert system.t < 0.05


def test_steps_within_the_tolerance_are_not_counted():
    system = pendulum_and_spring(StepControl(rtol=1e-4, atol=1e-4))
    with warnings.catch_warnings():
        warnings.simplefilter("error", SysSimXWarning)
        system.initialize(0.0)
        result = system.run(0.0, 1.0, 0.1)
    assert result.statistics.steps_over_tolerance == 0
    assert result.statistics.largest_error <= 1.0


def test_strict_must_be_true_or_false():
    with pytest.raises(ConfigurationError) as caught:
        StepControl(strict=1).validate("S")  # type: ignore[arg-type]
    assert "step_control.strict must be true or false, got 1" in str(caught.value)
