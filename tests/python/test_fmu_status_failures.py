"""What an FMU's failing statuses mean to a run: a discard that is no termination, fmi2Fatal
(after which nothing calls the FMU again), a failing fmi2GetReal, non-finite outputs (a run
stops where one feeds an input, and records one that feeds nothing); and numpy scalars as times
and steps."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from fixture_fmus import fmu_path
from syssimx import (
    Connection,
    CoSimComponent,
    FMUComponent,
    FMUError,
    PortSpec,
    PortType,
    SimulationError,
    System,
)
from syssimx.engine import lib, string
from syssimx.errors import SysSimXWarning

FAILURES = {"error": 0, "fatal": 1, "discard": 2, "read": 3, "nan": 4}


class Sink(CoSimComponent):
    """One input and nothing else: what an output feeds."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.input_specs["u"] = PortSpec(name="u", type=PortType.REAL, direction="in")

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _update_output_states(self, t: float | None = None, event_names=None) -> None:
        pass

    def snapshot_state(self) -> None:  # no state: it rolls back with any system
        return None

    def restore_state(self, snapshot: None, t: float) -> None:
        pass


def fed(system: System, component: str, output: str) -> System:
    """The system with the output connected to a sink's input."""
    system.add_component(Sink("Sink"))
    system.add_connection(Connection(component, output, "Sink", "u"))
    return system


def broken_system(failure: str) -> tuple[System, FMUComponent]:
    broken = FMUComponent("Broken", fmu_path("failing"))
    broken.set_parameters(fail_time=0.5, failure=FAILURES[failure])
    broken.set_inputs({"u": 2.0})
    system = System("S")
    system.add_component(broken)
    return system, broken


def test_a_discard_that_is_no_termination_names_the_last_successful_time():
    system, _ = broken_system("discard")
    system.initialize(0.0)
    with pytest.raises(SimulationError) as info:
        system.run(0.0, 1.0, 0.25)
    assert str(info.value) == (
        "component 'Broken': fmi2DoStep from t=0.5 to 0.75 returned fmi2Discard without asking "
        "to terminate: the FMU completed the step only up to fmi2LastSuccessfulTime=0.5 (FMU "
        "log: fmi2DoStep from t = 0.5 to 0.75: the simulation passed fail_time (a deliberate "
        "discard))")
    assert (info.value.component, info.value.time, info.value.status) == ("Broken", 0.5, 2)
    assert system.termination is None
    np.testing.assert_array_equal(system.get_history()["Broken"][0], [0.0, 0.25, 0.5])


def test_after_fmi2fatal_no_call_reaches_the_fmu():
    system, broken = broken_system("fatal")
    system.initialize(0.0)
    with pytest.raises(SimulationError, match=r"fmi2DoStep failed at t=0\.5 with status fmi2Fatal"):
        system.run(0.0, 1.0, 0.25)
    counters = broken.instance.counters()
    refused = ("refused: fmi2DoStep returned fmi2Fatal earlier, and FMI 2.0 allows no further "
               "call on the FMU")
    with pytest.raises(FMUError) as info:
        broken.instance.terminate()
    assert str(info.value) == f"Broken: fmi2Terminate returned failed: fmi2Terminate {refused}"
    with pytest.raises(FMUError) as info:
        broken.instance.getReal([0])
    assert str(info.value).endswith(f"fmi2GetReal {refused}")
    # the failing FMU logs any call it receives after fmi2Fatal (fmi2FreeInstance included):
    # the engine's own refusal staying the last message shows none reached it
    system.reset()
    assert string(lib().ssx_fmu_last_message(broken.instance.fmu)) == f"fmi2GetReal {refused}"
    with pytest.raises(FMUError) as info:
        system.initialize(0.0)
    assert str(info.value).endswith(f"fmi2Instantiate {refused}")
    assert broken.instance.counters() == counters


def test_a_failing_read_is_reported_at_the_end_of_the_step():
    system, _ = broken_system("read")
    system.initialize(0.0)
    with pytest.raises(SimulationError, match=r"fmi2GetReal failed at t=0\.75 ") as info:
        system.run(0.0, 1.0, 0.25)
    assert info.value.time == 0.75
    assert "a deliberate read failure" in info.value.fmu_message


def test_a_non_finite_output_stops_the_run_naming_the_port_and_the_time():
    system = fed(broken_system("nan")[0], "Broken", "y")
    system.initialize(0.0)
    with pytest.raises(SimulationError) as info:
        system.run(0.0, 1.0, 0.25)
    assert str(info.value) == ("component 'Broken': output 'y' is nan at t=0.75 (non-finite "
                               "values stop the run unless they are allowed)")
    assert (info.value.component, info.value.time) == ("Broken", 0.75)
    t, data = system.get_history()["Broken"]
    np.testing.assert_array_equal(t, [0.0, 0.25, 0.5])
    np.testing.assert_array_equal(data["y"], [2.0, 2.0, 2.0])


def test_non_finite_outputs_are_recorded_when_allowed():
    system, _ = broken_system("nan")
    system.initialize(0.0, allow_non_finite=True)
    t, data = system.run(0.0, 1.0, 0.25)["Broken"]
    np.testing.assert_array_equal(t, [0.0, 0.25, 0.5, 0.75, 1.0])
    assert data["y"][:3].tolist() == [2.0, 2.0, 2.0] and np.isnan(data["y"][3:]).all()
    fed(system, "Broken", "y")
    system.initialize(0.0)  # each initialize starts from the engine's default: stop
    with pytest.raises(SimulationError, match="output 'y' is nan"):
        system.run(0.0, 1.0, 0.25)


@pytest.mark.parametrize(("t0", "tf", "dt"), [
    (np.float32(0), np.float32(1), np.float32(0.25)),
    (np.float64(0), np.float64(1), np.float64(0.25)),
    (np.int64(0), np.int32(2), np.int16(1)),
])
def test_numpy_scalars_are_accepted_as_times_and_steps(t0, tf, dt):
    ramp = FMUComponent("Ramp", fmu_path("terminating"))
    ramp.set_parameters(stop_time=10.0)
    system = System("S")
    system.add_component(ramp)
    system.initialize(t0)
    t, data = system.run(t0, tf, dt)["Ramp"]
    np.testing.assert_array_equal(t, np.arange(0, float(tf) + 0.5 * float(dt), float(dt)))
    np.testing.assert_array_equal(data["y"], t)
    assert type(system.t) is float and system.t == float(tf)


class Reciprocal(CoSimComponent):
    """y = 1 / (1 - t): infinite at t = 1 (a Python component)."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.output_specs["y"] = PortSpec(name="y", type=PortType.REAL, direction="out")

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _update_output_states(self, t: float | None = None, event_names=None) -> None:
        now = 0.0 if t is None else t
        self.outputs["y"].set(math.inf if now == 1.0 else 1.0 / (1.0 - now), t)


def test_a_python_component_with_an_infinite_output_stops_the_run_too():
    system = System("S")
    system.add_component(Reciprocal("R"))
    fed(system, "R", "y")
    system.initialize(0.0)
    with pytest.raises(SimulationError) as info:
        system.run(0.0, 2.0, 0.5)
    assert str(info.value) == ("component 'R': output 'y' is inf at t=1 (non-finite values stop "
                               "the run unless they are allowed)")
    np.testing.assert_array_equal(system.get_history()["R"][1]["y"], [1.0, 2.0])


def late_nan_system(stem: str) -> tuple[System, FMUComponent]:
    """late_nan's y = t feeds a sink; its `limit` is 1, then NaN from t = 0.5, and feeds
    nothing (libcosim's 20-sim KnuckleBoomCrane: Act_Limits[1] NaN from t = 2.048)."""
    late = FMUComponent("Crane", fmu_path(stem))
    system = System("S")
    system.add_component(late)
    return fed(system, "Crane", "y"), late


@pytest.mark.parametrize("stem", ["late_nan", "late_nan_fmi3"])
def test_a_non_finite_output_that_feeds_nothing_is_recorded_and_warned_once(stem):
    """Before: the run stopped at t=0.5 ("non-finite values stop the run unless they are
    allowed"); FMPy records the NaN and goes on."""
    system, _ = late_nan_system(stem)
    system.initialize(0.0)
    with pytest.warns(SysSimXWarning) as warned:
        result = system.run(0.0, 1.0, 0.25)
    assert [str(w.message) for w in warned] == [
        "Crane: output 'limit' is NaN or infinite from t=0.5; it feeds no input and no event "
        "indicator, so it is recorded as it is and the run goes on"]
    t, data = result["Crane"]
    np.testing.assert_array_equal(t, [0.0, 0.25, 0.5, 0.75, 1.0])
    np.testing.assert_array_equal(data["y"], t)
    assert data["limit"][:2].tolist() == [1.0, 1.0] and np.isnan(data["limit"][2:]).all()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # warned once: the next run says nothing again
        system.run(1.0, 1.5, 0.25)


def test_a_non_finite_output_that_feeds_an_input_still_stops_the_run():
    system, _ = late_nan_system("late_nan")
    system.add_component(Sink("Limiter"))
    system.add_connection(Connection("Crane", "limit", "Limiter", "u"))
    system.initialize(0.0)
    with pytest.raises(SimulationError) as info:
        system.run(0.0, 1.0, 0.25)
    assert str(info.value) == ("component 'Crane': output 'limit' is nan at t=0.5 (non-finite "
                               "values stop the run unless they are allowed)")


def test_a_non_finite_output_watched_by_an_event_indicator_still_stops_the_run():
    system, late = late_nan_system("late_nan")
    late.add_event_indicator("limit_reached", variable="limit", direction=-1)
    system.initialize(0.0)
    with pytest.raises(SimulationError, match=r"output 'limit' is nan at t=0\.5 "):
        system.run(0.0, 1.0, 0.25)
