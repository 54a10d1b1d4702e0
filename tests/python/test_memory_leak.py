"""Systems with Python callbacks are freed when dropped (issue 9, item 3): handlers,
indicators and Python components no longer keep their System alive."""

from __future__ import annotations

import gc
import logging
import os
import weakref
from pathlib import Path
from typing import Any

import pytest
from syssimx import CoSimComponent, EventConnection, FMUComponent, PortSpec, PortType, System, fmus


class Ramp(CoSimComponent):
    """y = t with rollback: a Python component with a Python indicator and handler."""

    def __init__(self) -> None:
        super().__init__("R")
        self.output_specs["y"] = PortSpec("y", PortType.REAL, "out")
        self.y = 0.0
        self.handled: list[float] = []

    def _initialize_component(self, t0: float) -> None:
        self.y = t0

    def _do_step_internal(self, t: float, dt: float) -> None:
        self.y = t + dt

    def _update_output_states(self, t: float | None = None, event_names: Any = None) -> None:
        self.outputs["y"].set(self.y, t)

    def snapshot_state(self) -> float:
        return self.y

    def restore_state(self, snapshot: float, t: float) -> None:
        self.y = snapshot


def ramp_system() -> System:
    ramp = Ramp()
    ramp.add_event_indicator("half", func=lambda c: c.y - 0.5, direction=1)
    ramp.add_event_handler("on_half", lambda c, events, t: c.handled.append(t))
    system = System("ramp")
    system.add_component(ramp)
    system.add_event_connection(EventConnection("R", "half", "R", "on_half"))
    return system


def fmu_handler_system() -> System:
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.set_parameters(theta0=0.5, omega0=0.0)
    pendulum.add_event_indicator("wall_hit", variable="theta", direction=-1)
    pendulum.add_event_handler("bounce", lambda comp, events, t: comp.reinitialize(
        t, theta0=0.0, omega0=-comp.get_outputs()["omega"].magnitude))
    system = System("wall")
    system.add_component(pendulum)
    system.add_event_connection(EventConnection("P", "wall_hit", "P", "bounce"))
    return system


def run_and_watch(system: System, tf: float) -> tuple[weakref.ref[Any], weakref.ref[Any]]:
    system.initialize(0.0)
    result = system.run(0.0, tf, 0.1)
    assert len(result.events) == 1  # the callbacks really ran
    return weakref.ref(system), weakref.ref(system._plan)


def test_a_system_with_python_callbacks_and_its_engine_plan_are_collected():
    for build, tf in ((ramp_system, 1.0), (fmu_handler_system, 0.6)):
        system_ref, plan_ref = run_and_watch(build(), tf)
        gc.collect()
        assert system_ref() is None, build.__name__
        assert plan_ref() is None, build.__name__


def test_results_outlive_their_collected_system():
    system = ramp_system()
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.25)
    plan_ref = weakref.ref(system._plan)
    del system
    gc.collect()
    assert plan_ref() is None
    t, data = result["R"]
    assert list(t) == [0.0, 0.25, 0.5, 0.5, 0.75, 1.0]
    assert list(data["y"]) == [0.0, 0.25, 0.5, 0.5, 0.75, 1.0]


def resident_bytes() -> int:
    return int(Path("/proc/self/statm").read_text().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_a_thousand_systems_with_handlers_leave_the_resident_size_flat(
        caplog: pytest.LogCaptureFixture) -> None:
    # an example run in the same session may have set syssimx's loggers to DEBUG: the log
    # records of 1000 runs would be kept by pytest's log capture and grow the process
    caplog.set_level(logging.WARNING, logger="syssimx")

    def one_system() -> None:
        system = ramp_system()
        system.initialize(0.0)
        system.run(0.0, 1.0, 0.05)

    for _ in range(100):  # allocator pools and caches reach their working size
        one_system()
    gc.collect()
    before = resident_bytes()
    for _ in range(1000):
        one_system()
    gc.collect()
    # A System here holds about 20 kB (Python objects, engine system, 22 samples); the plan
    # leaked with all of it, so 1000 leaked Systems grow the process by 20 MB and more. 4 MB
    # leaves room for allocator noise and is below 4 kB per System.
    assert resident_bytes() - before < 4e6
