"""A component's own events as an event source: listeners subscribed to them.

bouncing_ball_cvode run as Model Exchange bounces at the closed-form times inside its own steps
(the engine's CVODE finds them as roots), the FMI 3.0 Co-Simulation ball returns early at each
and is handled in event mode; a Python handler subscribed to those events is called once per
bounce with the bounce's exact time, and a Reinitialize subscribed to them restarts
another FMU at the communication point that holds the bounce. Beside a master indicator
located by rollback, each bounce still reaches its listener once, and the master's events are
those without the ball (master indicators: test_hybrid_events.py, test_declarative_events.py).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from syssimx import (
    ConfigurationError,
    EventConnection,
    FMUComponent,
    HybridAlgorithm,
    Reinitialize,
    System,
    TableSource,
    fmus,
)
from syssimx.engine import ffi, lib
from syssimx.system.loader import build_system

G = 9.81
DT = 0.01


def bounce_times(e: float = 0.8, gap_tol: float = 1e-6, h0: float = 1.0) -> list[float]:
    """From h0 at rest: v := -e v at h = 0, at rest once a rebound would rise less than
    gap_tol."""
    times, t, speed = [], math.sqrt(2 * h0 / G), math.sqrt(2 * G * h0)
    while True:
        times.append(t)
        speed *= e
        if speed**2 <= 2 * G * gap_tol:
            return times
        t += 2 * speed / G


def ball(name: str, interface: str = "model-exchange") -> FMUComponent:
    return FMUComponent(name, fmus.path("bouncing_ball_cvode"), interface=interface,
                        tolerance=1e-12)


def test_a_python_listener_of_own_events_is_called_at_each_bounce_time():
    calls: list[tuple[list[str], float]] = []
    b = ball("B")
    b.add_event_handler("bounced", lambda _c, names, t: calls.append((names, t)))
    system = System("ball")
    system.add_component(b)
    system.add_event_connection(EventConnection.own_events("B", "B", "bounced"))
    system.initialize(0.0)
    result = system.run(0.0, 3.0, DT)
    expected = [t for t in bounce_times() if t < 3.0]
    assert len(calls) == len(expected) == 6
    assert all(names == ["own_events"] for names, _ in calls)
    # CVODE at 1e-12 locates each root within 1e-8 of the closed form (as the own event
    # records do: test_model_exchange.py); the listener gets the record's time itself
    assert np.max(np.abs(np.array([t for _, t in calls]) - expected)) < 1e-8
    assert [t for _, t in calls] == [e.t for e in result.events]
    # a listener of own events changes nothing the ball does: no rollback, no extra step
    assert (result.statistics.own_events, result.statistics.state_restores,
            result.statistics.do_step_calls) == (6, 0, 300)


@pytest.mark.parametrize("through_python", [False, True])
def test_a_reinitialize_listener_restarts_another_fmu_at_the_communication_point(
        through_python: bool):
    """B2 (a Co-Simulation ball from h0 = 2, no floor reached before t = 0.63) restarts from
    rest whenever B bounces: at the grid point after each bounce it is back at h0, and falls
    freely from there. The engine runs the Reinitialize, or Python when another handler shares
    the input: both restart where B2 stands."""
    b, b2 = ball("B"), ball("B2", interface="co-simulation")
    b2.set_parameters(h0=2.0)
    b2.add_event_handler("restart", Reinitialize(h0=2.0))
    if through_python:
        b2.add_event_handler("restart", lambda *_: None)
    system = System("two balls")
    system.add_component(b)
    system.add_component(b2)
    system.add_event_connection(EventConnection.own_events("B", "B2", "restart"))
    system.initialize(0.0)
    t, values = system.run(0.0, 1.0, DT)["B2"]
    first = bounce_times()[0]  # 0.4515...: committed at the step ending 0.46
    restart = math.ceil(first / DT) * DT
    fall = t < restart - 1e-9
    np.testing.assert_allclose(values["h"][fall], 2.0 - G * t[fall] ** 2 / 2, atol=1e-9)
    after = t > restart - 1e-9
    np.testing.assert_allclose(values["h"][after], 2.0 - G * (t[after] - restart) ** 2 / 2,
                               atol=1e-9)


def test_own_events_come_only_from_fmu_components():
    rows = np.array([(0.0, 0.0), (1.0, 1.0)], dtype=[("time", float), ("y", float)])
    table = TableSource("T", rows)
    b = ball("B")
    b.add_event_handler("bounced", lambda *_: None)
    system = System("s")
    system.add_component(table)
    system.add_component(b)
    with pytest.raises(ConfigurationError,
                       match=r"T\.own_events -> B\.bounced: 'T' handles no events of its own"):
        system.add_event_connection(EventConnection.own_events("T", "B", "bounced"))


def test_the_engine_names_a_bad_event_source():
    sys = lib().ssx_system_new(b"s")
    try:
        assert lib().ssx_subscribe(sys, 7, 0, 0) == -1
        assert "unknown event source kind 7" in ffi.string(lib().ssx_last_error(sys).message
                                                           ).decode()
        assert lib().ssx_subscribe(sys, lib().SSX_SOURCE_OWN_EVENTS, 3, 0) == -1
        assert "3" in ffi.string(lib().ssx_last_error(sys).message).decode()
    finally:
        lib().ssx_system_free(sys)


def test_own_events_reach_their_listener_once_while_the_master_locates_its_own():
    """Beside the seed's pendulum and its wall (a master indicator, located by rollback), the
    ball's bounces reach the listener once each, at their times, however often the
    localization steps the ball again; the wall hits are those of the pendulum alone."""
    calls: list[float] = []

    def seed(with_ball: bool) -> list[float]:
        pendulum = FMUComponent("P", fmus.path("pendulum_cvode"))
        pendulum.set_parameters(theta0=0.5, omega0=0.0, cvode_relative_tolerance=1e-10)
        pendulum.add_event_indicator("wall_hit", variable="theta", direction=-1)
        pendulum.add_event_handler("omega_invert", Reinitialize(theta0="theta", omega0="-omega"))
        system = System("wall")
        system.add_component(pendulum)
        system.add_event_connection(EventConnection("P", "wall_hit", "P", "omega_invert"))
        if with_ball:
            b = ball("B")
            b.add_event_handler("bounced", lambda _c, _names, t: calls.append(t))
            system.add_component(b)
            system.add_event_connection(EventConnection.own_events("B", "B", "bounced"))
        system.set_algorithm(HybridAlgorithm(tol_time=1e-9, tol_value=1e-9))
        system.initialize(0.0)
        result = system.run(0.0, 2.0, 0.05)
        assert result.statistics.state_restores > 0  # the wall was located by rollback
        return [e.t for e in result.events if e.component == "P"]

    assert seed(with_ball=True) == seed(with_ball=False)
    expected = [t for t in bounce_times() if t < 2.0]
    assert len(calls) == len(expected) == 3
    assert np.max(np.abs(np.array(calls) - expected)) < 1e-8


def test_an_fmi3_fmus_events_in_its_step_reach_their_listener():
    """The FMI 3.0 ball (Co-Simulation, its own CVODE) returns early at each bounce and is
    handled in event mode inside its step: the listener gets each closed-form time."""
    calls: list[float] = []
    b = FMUComponent("B", fmus.path("bouncing_ball_cvode_fmi3"))
    b.set_parameters(h0=1.0, v0=0.0, g=G, e=0.8, cvode_relative_tolerance=1e-12)
    b.add_event_handler("bounced", lambda _c, _names, t: calls.append(t))
    system = System("fmi3 ball")
    system.add_component(b)
    system.add_event_connection(EventConnection.own_events("B", "B", "bounced"))
    system.initialize(0.0)
    result = system.run(0.0, 3.0, DT)
    expected = [t for t in bounce_times() if t < 3.0]
    assert len(calls) == len(expected) == 6
    assert np.max(np.abs(np.array(calls) - expected)) < 1e-8
    assert calls == [e.t for e in result.events]


def test_a_system_file_subscribes_to_own_events_by_the_port_own_events(tmp_path: Path):
    """The YAML form of the Reinitialize test above (at the FMUs' default tolerances: the
    samples within 1e-6 of the free fall from the restart)."""
    config = tmp_path / "balls.yaml"
    config.write_text(
        "system: {name: balls}\n"
        "components:\n"
        "  - {name: B, fmu: bouncing_ball_cvode, interface: model-exchange}\n"
        "  - name: B2\n"
        "    fmu: bouncing_ball_cvode\n"
        "    interface: co-simulation\n"
        "    parameters: {h0: 2.0}\n"
        "    event_handlers: [{input: restart, reinitialize: {h0: 2.0}}]\n"
        "event_connections: [{src: B.own_events, dst: B2.restart}]\n")
    system = build_system(config)
    system.initialize(0.0)
    t, values = system.run(0.0, 1.0, DT)["B2"]
    restart = math.ceil(bounce_times()[0] / DT) * DT
    after = t > restart - 1e-9
    assert after.sum() > 50
    np.testing.assert_allclose(values["h"][after], 2.0 - G * (t[after] - restart) ** 2 / 2,
                               atol=1e-6)
