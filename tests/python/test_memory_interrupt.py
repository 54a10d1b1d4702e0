"""Runs can be stopped (issue 9, item 5): Ctrl-C and timeout= stop a run between macro steps
with the samples up to there kept, and a run reserves no history up front.

The bounds on wall time are loose on purpose: without the fix each of these runs would take
hours (10^9 macro steps), or fail at once reserving tens of GB."""

from __future__ import annotations

import os
import signal
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from syssimx import (
    EventConnection,
    FMUComponent,
    SimulationTimeoutError,
    System,
    fmus,
)

HUGE_DT = 1e-9  # 10^9 macro steps per simulated second: a typo for 1e-3


def pendulum(name: str = "P") -> FMUComponent:
    component = FMUComponent(name, fmus.path("pendulum_euler"))
    component.set_parameters(theta0=0.5, omega0=0.0)
    return component


def resident_bytes() -> int:
    return int(Path("/proc/self/statm").read_text().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def interrupt_after(seconds: float) -> threading.Timer:
    timer = threading.Timer(seconds, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    return timer


def assert_samples_up_to_the_stop(system: System, dt: float) -> None:
    t, data = system.get_history()["P"]
    assert len(t) > 1000
    np.testing.assert_allclose(np.diff(t), dt, rtol=1e-6)
    assert t[-1] == pytest.approx(system.t, abs=1e-15)
    assert np.all(np.isfinite(data["theta"])) and data["theta"][0] == 0.5


def test_ctrl_c_stops_a_huge_run_quickly_with_samples_and_without_reserving_it():
    system = System("typo")
    system.add_component(pendulum())
    system.initialize(0.0)
    before = resident_bytes()
    interrupt_after(0.3)
    start = time.monotonic()
    # timeout only guards the test itself against hanging for hours without the fix
    with pytest.raises(KeyboardInterrupt):
        system.run(0.0, 1.0, HUGE_DT, timeout=30.0)
    assert time.monotonic() - start < 5.0
    assert_samples_up_to_the_stop(system, HUGE_DT)
    # 36 B per sample: the whole grid would be 36 GB. The engine holds the samples recorded
    # (its room ahead is given back when the run stops), and only those were made resident
    recorded = len(system.get_history()["P"][0]) * (8 + 4 + 3 * 8)
    assert system.history_bytes() == recorded
    assert resident_bytes() - before < 2 * recorded + 64e6


def test_ctrl_c_in_a_hybrid_run_with_a_python_handler_is_a_keyboard_interrupt():
    # the indicator is evaluated in C and the handler is Python: no Python runs per step
    component = pendulum()
    component.add_event_indicator("wall_hit", variable="theta", direction=-1)
    component.add_event_handler("bounce", lambda comp, events, t: None)
    system = System("hybrid")
    system.add_component(component)
    system.add_event_connection(EventConnection("P", "wall_hit", "P", "bounce"))
    system.initialize(0.0)
    interrupt_after(0.3)
    with pytest.raises(KeyboardInterrupt):
        system.run(0.0, 1.0, HUGE_DT, timeout=30.0)
    assert_samples_up_to_the_stop(system, HUGE_DT)


def test_timeout_stops_the_run_with_a_clear_error_and_keeps_the_samples():
    system = System("slow")
    system.add_component(pendulum())
    system.initialize(0.0)
    start = time.monotonic()
    with pytest.raises(SimulationTimeoutError,
                       match=r"system 'slow': the run exceeded timeout=0.2 s of wall time and "
                             r"stopped at t=") as caught:
        system.run(0.0, 1.0, HUGE_DT, timeout=0.2)
    assert 0.2 <= time.monotonic() - start < 5.0
    assert isinstance(caught.value, TimeoutError)
    assert caught.value.time == pytest.approx(system.t, abs=1e-15)
    assert_samples_up_to_the_stop(system, HUGE_DT)
    # the system goes on from where it stopped
    t_stop = system.t
    result = system.run(t_stop, t_stop + 1e-3, 1e-4)
    assert result["P"][0][-1] == t_stop + 1e-3


def test_a_run_within_its_timeout_is_not_disturbed():
    system = System("quick")
    system.add_component(pendulum())
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.01, timeout=60.0)
    assert result["P"][0][-1] == 1.0 and len(result["P"][0]) == 101
