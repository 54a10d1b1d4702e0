"""Misuse is refused with fmi2Error and a logged message naming the problem."""

from __future__ import annotations

import math

import pytest
from fmpy.fmi1 import FMICallException

FMI2_ERROR = 3


def refused(fmu, call, *args, expected: str) -> None:
    count = len(fmu.messages)
    with pytest.raises(FMICallException) as failure:
        call(*args)
    assert failure.value.status == FMI2_ERROR
    assert len(fmu.messages) > count
    status, message = fmu.messages[-1]
    assert status == FMI2_ERROR
    assert expected in message


@pytest.mark.parametrize("name", ["pendulum_euler", "pendulum_cvode"])
def test_bad_calls_in_step_mode(open_fmu, name: str) -> None:
    fmu = open_fmu(name)
    refused(fmu, fmu.slave.doStep, 0.0, -0.1, expected="negative")
    refused(fmu, fmu.slave.doStep, 0.0, math.nan, expected="negative or not finite")
    refused(fmu, fmu.slave.doStep, 0.3, 0.1, expected="differs from the FMU's time")
    refused(fmu, fmu.slave.getReal, [4242], expected="unknown value reference 4242")
    refused(fmu, fmu.slave.setReal, [fmu.vr("m")], [50.0], expected="fixed parameter")
    refused(fmu, fmu.slave.enterInitializationMode, expected="not allowed in step mode")
    fmu.slave.doStep(0.0, 0.1)  # still usable
    assert fmu.get("m") == 40.0


def test_step_before_initialization_is_refused(open_fmu) -> None:
    fmu = open_fmu("pendulum_euler", initialize=False)
    refused(fmu, fmu.slave.doStep, 0.0, 0.1, expected="not allowed in instantiated")


def test_wrong_guid_is_refused(open_fmu) -> None:
    with pytest.raises(Exception, match="Failed to instantiate"):
        open_fmu("pendulum_euler", guid="{00000000-0000-0000-0000-000000000000}")


def test_failing_fmu_reports_why(open_fmu) -> None:
    fmu = open_fmu("failing", starts={"fail_time": 0.2})
    fmu.slave.doStep(0.0, 0.2)
    refused(fmu, fmu.slave.doStep, 0.2, 0.1, expected="passed fail_time")


@pytest.mark.parametrize("name", ["pendulum_euler", "pendulum_cvode"])
def test_masters_habits_after_a_restore_are_accepted(open_fmu, name: str) -> None:
    """SysSimX re-applies every parameter after fmi2SetFMUstate and, after an event, steps from
    the event time plus its tol_time (1e-8 by default): unchanged parameters and a skip of that
    size are accepted; the FMU keeps integrating from its own time."""
    fmu = open_fmu(name, starts={"theta0": 0.5})
    fmu.slave.doStep(0.0, 0.1)
    state = fmu.slave.getFMUstate()
    fmu.slave.doStep(0.1, 0.1)
    fmu.slave.setFMUstate(state)
    count = len(fmu.messages)
    # every parameter, the back-end's included, as SysSimX's _apply_parameters_starts does
    backend = "euler_step_size" if name.endswith("euler") else "cvode_relative_tolerance"
    names = ["m", "theta0", backend]
    fmu.slave.setReal([fmu.vr(n) for n in names], [fmu.get(n) for n in names])
    fmu.slave.doStep(0.1 + 1e-8, 0.1)
    assert len(fmu.messages) == count  # nothing to complain about
    theta_skipped = fmu.get("theta")
    fmu.slave.setFMUstate(state)
    fmu.slave.doStep(0.1, 0.1 + 1e-8)
    # the same interval [0.1, 0.2 + 1e-8], up to the rounding of its end point
    assert fmu.get("theta") == pytest.approx(theta_skipped, abs=1e-12)
    refused(fmu, fmu.slave.setReal, [fmu.vr("theta0")], [0.25], expected="fixed parameter")
    refused(fmu, fmu.slave.setReal, [fmu.vr(backend)], [0.5 * fmu.get(backend)],
            expected="fixed parameter")
    fmu.slave.freeFMUstate(state)
