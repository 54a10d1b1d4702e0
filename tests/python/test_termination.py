"""An FMU that asks to stop (fmi2Discard with fmi2Terminated) ends the run cleanly: the result
says which component stopped and when, and ends at the last communication point the whole system
completed. Checked on our Terminating ramp and on the Reference FMU Stair against FMPy."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
from fixture_fmus import fmu_path
from fmpy import simulate_fmu
from syssimx import (
    EventConnection,
    FMUComponent,
    SimulationError,
    System,
    Termination,
)


def ramp_system(stop_time: float = 1.0, y0: float = 0.0) -> tuple[System, FMUComponent]:
    ramp = FMUComponent("Ramp", fmu_path("terminating"))
    ramp.set_parameters(stop_time=stop_time, y0=y0)
    system = System("S")
    system.add_component(ramp)
    return system, ramp


def test_a_stop_inside_a_step_ends_the_run_at_the_step_start():
    system, _ = ramp_system()
    system.initialize(0.0)
    result = system.run(0.0, 2.0, 0.3)
    t, data = result["Ramp"]
    np.testing.assert_allclose(t, [0.0, 0.3, 0.6, 0.9], rtol=0, atol=1e-15)
    np.testing.assert_allclose(data["y"], t, rtol=0, atol=1e-15)
    assert result.termination == Termination(
        "Ramp", 1.0, "fmi2DoStep from t = 0.89999999999999991 to 1.2: the model asks to end the "
                     "simulation at t = 1")
    assert system.termination == result.termination
    assert system.t == pytest.approx(0.9, abs=1e-15)
    assert result.statistics.do_step_calls == 4
    lines = str(result.statistics).splitlines()
    assert lines[-1] == "terminated: component 'Ramp' asked to stop at t = 1"
    assert lines[:2] == ["macro steps: 3", "doStep calls: 4"]


def test_a_stop_at_a_communication_point_matches_fmpy():
    system, _ = ramp_system()
    system.initialize(0.0)
    result = system.run(0.0, 2.0, 0.25)
    t, data = result["Ramp"]
    reference = simulate_fmu(fmu_path("terminating"), stop_time=2.0, output_interval=0.25,
                             start_values={"stop_time": 1.0})
    np.testing.assert_array_equal(t, reference["time"])
    np.testing.assert_array_equal(data["y"], reference["y"])
    assert t[-1] == 1.0 and result.termination.time == 1.0


def test_the_components_after_the_stopping_one_complete_the_step():
    system, _ = ramp_system()
    later = FMUComponent("Later", fmu_path("terminating"))
    later.set_parameters(stop_time=5.0, slope=3.0)
    system.add_component(later)
    system.initialize(0.0)
    result = system.run(0.0, 2.0, 0.25)
    t, data = result["Later"]
    np.testing.assert_array_equal(t, [0.0, 0.25, 0.5, 0.75, 1.0])
    np.testing.assert_array_equal(data["y"], 3.0 * t)
    assert later.instance.counters()["do_step"] == 4
    assert result.termination.component == "Ramp"


def test_a_later_run_is_an_error_naming_the_termination_until_initialize():
    system, _ = ramp_system()
    system.initialize(0.0)
    system.run(0.0, 2.0, 0.25)
    with pytest.raises(SimulationError) as info:
        system.run(1.0, 2.0, 0.25)
    assert str(info.value) == ("system 'S' ended at t=1: component 'Ramp' asked to stop at t=1; "
                               "initialize the system again to start a new run")
    assert len(system.get_history()["Ramp"][0]) == 5  # the samples stay readable
    system.initialize(0.0)
    assert system.termination is None
    result = system.run(0.0, 0.5, 0.25)
    assert result.termination is None
    assert "terminated" not in str(result.statistics)


def test_hybrid_events_before_the_stop_are_handled_and_one_in_the_stopping_step_is_not():
    def run(y0: float) -> tuple[System, object]:
        system, ramp = ramp_system(y0=y0)
        ramp.add_event_indicator("up", variable="y", direction=1)
        ramp.add_event_handler("seen", lambda component, events, t: None)
        system.add_event_connection(EventConnection("Ramp", "up", "Ramp", "seen"))
        system.initialize(0.0)
        return system, system.run(0.0, 2.0, 0.25)

    # the crossing at 0.5 is located and handled; the run then completes the step to 1.0
    system, result = run(-0.5)
    assert [e.t for e in result.events] == pytest.approx([0.5], abs=1e-9)
    assert result["Ramp"][0][-1] == 1.0 and result.termination.time == 1.0
    # the crossing at 0.95 lies in the step that stops: locating it would step the stopped FMU
    # again, so the run ends at 0.75, the last accepted instant
    system, result = run(-0.95)
    assert result.events == []
    assert result["Ramp"][0][-1] == 0.75 and system.t == 0.75
    assert result.termination == Termination("Ramp", 1.0, result.termination.message)


def _reference_fmus() -> Path | None:
    candidates = [os.environ.get("SYSSIMX_REFERENCE_FMUS"),
                  Path(__file__).resolve().parents[2].parent / "shared" / "reference-fmus"]
    for candidate in candidates:
        if candidate and (Path(candidate) / "fmi2" / "Stair.fmu").is_file():
            return Path(candidate) / "fmi2"
    return None


@pytest.mark.parametrize("dt", [0.2, 0.5])
def test_reference_stair_ends_at_9_like_fmpy(dt: float):
    folder = _reference_fmus()
    if folder is None:
        pytest.skip("the Reference FMUs are absent: set SYSSIMX_REFERENCE_FMUS or put them in "
                    "../shared/reference-fmus")
    stair = FMUComponent("Stair", folder / "Stair.fmu")
    system = System("stairs")
    system.add_component(stair)
    system.initialize(0.0)
    result = system.run(0.0, 10.0, dt)
    reference = simulate_fmu(folder / "Stair.fmu", stop_time=10.0, output_interval=dt)
    t, data = result["Stair"]
    np.testing.assert_allclose(t, reference["time"], rtol=1e-12, atol=0)
    np.testing.assert_array_equal(data["counter"], reference["counter"])
    assert t[-1] == pytest.approx(9.0, rel=1e-12) and data["counter"][-1] == 10
    assert result.termination.component == "Stair"
    assert result.termination.time == pytest.approx(9.0, rel=1e-12)
    assert str(result.statistics).splitlines()[-1] == \
        "terminated: component 'Stair' asked to stop at t = 9"


class Substepping(FMUComponent):
    """Overrides the step hook like the seed's subclass, stepping through the built-in."""

    def _do_step_internal(self, t: float, dt: float) -> None:
        super()._do_step_internal(t, dt)


def test_a_stop_reached_through_a_python_step_hook_also_ends_the_run():
    ramp = Substepping("Ramp", fmu_path("terminating"))
    ramp.set_parameters(stop_time=1.0)
    system = System("S")
    system.add_component(ramp)
    system.initialize(0.0)
    result = system.run(0.0, 2.0, 0.3)
    assert result["Ramp"][0][-1] == pytest.approx(0.9, abs=1e-15)
    assert result.termination.component == "Ramp" and result.termination.time == 1.0
