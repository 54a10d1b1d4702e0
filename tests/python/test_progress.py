"""System.run(..., progress=...): SysSimX's progress(t, tf) callback, called from the engine's
monitor (never once per step from Python) and exactly once at the end of the run; True shows a
terminal bar once a run has lasted a second."""

from __future__ import annotations

import io
import time

import pytest
from fixture_fmus import fmu_path
from quickstart import Integrator, LinearSource
from syssimx import (
    ConfigurationError,
    Connection,
    FMUComponent,
    GaussSeidelAlgorithm,
    SimulationError,
    System,
)
from syssimx.system.progress import ProgressBar

STEP_PAUSE = 0.004  # s of wall time per step of the slow integrator


class SlowIntegrator(Integrator):
    """The quickstart integrator, pausing in every step so that a run lasts long enough for
    the monitor (every ~50 ms of wall time) to report several times."""

    def _do_step_internal(self, t: float, dt: float) -> None:
        time.sleep(STEP_PAUSE)
        super()._do_step_internal(t, dt)


def quickstart(integrator: type[Integrator] = Integrator) -> System:
    system = System("QuickstartSystem")
    system.add_component(LinearSource("LinearSource"))
    system.add_component(integrator("Integrator"))
    system.add_connection(Connection("LinearSource", "y", "Integrator", "u"))
    system.set_algorithm(GaussSeidelAlgorithm())
    system.initialize(0.0)
    return system


def test_the_end_of_a_short_run_is_reported_once():
    calls: list[tuple[float, float]] = []
    result = quickstart().run(0.0, 5.0, 0.1, progress=lambda t, tf: calls.append((t, tf)))
    assert calls[-1] == (5.0, 5.0)
    assert len(calls) == len(set(calls))  # the end is not reported twice
    assert result["Integrator"][1]["y"][-1] == pytest.approx(12.25, abs=1e-12)


def test_reports_of_a_long_run_increase_within_the_run_and_end_at_tf():
    calls: list[tuple[float, float]] = []
    steps = 100  # at least 0.4 s of wall time: the monitor reports several times
    quickstart(SlowIntegrator).run(0.0, 10.0, 0.1, progress=lambda t, tf: calls.append((t, tf)))
    times = [t for t, _ in calls]
    assert len(calls) >= 3
    assert all(tf == 10.0 for _, tf in calls)
    assert all(0.0 < t <= 10.0 for t in times)
    assert times == sorted(set(times))  # strictly increasing
    assert times[-1] == 10.0
    assert len(calls) < steps  # not one call per step


def test_a_continued_run_reports_its_own_end():
    system = quickstart()
    calls: list[tuple[float, float]] = []
    system.run(0.0, 1.0, 0.1, progress=lambda t, tf: calls.append((t, tf)))
    system.run(1.0, 2.0, 0.1, progress=lambda t, tf: calls.append((t, tf)))
    assert calls[-1] == (2.0, 2.0) and (1.0, 1.0) in calls


def test_a_run_a_component_ends_reports_where_it_ended():
    ramp = FMUComponent("Ramp", fmu_path("terminating"))
    ramp.set_parameters(stop_time=1.0, y0=0.0)
    system = System("S")
    system.add_component(ramp)
    system.initialize(0.0)
    calls: list[tuple[float, float]] = []
    result = system.run(0.0, 2.0, 0.3, progress=lambda t, tf: calls.append((t, tf)))
    assert result.termination is not None
    assert calls[-1] == (pytest.approx(0.9, abs=1e-15), 2.0)


def test_a_failing_callback_fails_the_run_naming_it():
    def broken(t: float, tf: float) -> None:
        raise ValueError("no room on the screen")

    system = quickstart()
    with pytest.raises(ValueError, match="no room on the screen"):
        system.run(0.0, 1.0, 0.1, progress=broken)
    assert system.t == 1.0  # the run itself completed; the final report failed


def test_a_failing_callback_inside_the_run_stops_it_with_a_simulation_error():
    def broken(t: float, tf: float) -> None:
        raise ValueError("no room on the screen")

    system = quickstart(SlowIntegrator)
    with pytest.raises(SimulationError, match="monitor raised ValueError: no room on the screen"):
        system.run(0.0, 10.0, 0.1, progress=broken)
    assert 0.0 < system.t < 10.0
    t, _ = system.get_history()["Integrator"]
    assert t[-1] == pytest.approx(system.t, abs=1e-12)  # the samples up to there stay


def test_progress_must_be_a_flag_or_a_callable():
    system = quickstart()
    with pytest.raises(ConfigurationError, match=r"QuickstartSystem: progress must be True, "
                                                 r"False, None or a callable progress\(t, tf\), "
                                                 r"got 'yes'"):
        system.run(0.0, 1.0, 0.1, progress="yes")


def test_true_shows_no_bar_for_a_run_shorter_than_a_second(capsys: pytest.CaptureFixture[str]):
    quickstart().run(0.0, 5.0, 0.1, progress=True)
    assert capsys.readouterr() == ("", "")


def test_the_bar_shows_simulated_time():
    stream = io.StringIO()
    bar = ProgressBar(0.0, stream=stream, delay=0.0)
    bar(2.5, 5.0)
    bar(5.0, 5.0)
    bar.close()
    text = stream.getvalue()
    assert "2.5/5 s simulated" in text and "5/5 s simulated" in text
