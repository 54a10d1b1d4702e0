"""Event bookkeeping with a Python clock (x = t exactly, so crossings are known exactly)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest
from syssimx import (
    CoSimComponent,
    EventConnection,
    PortSpec,
    PortType,
    SimulationError,
    System,
)


class Clock(CoSimComponent):
    """x' = 1; rolls back by saving x."""

    def __init__(self, name: str = "C"):
        super().__init__(name)
        self.output_specs["x"] = PortSpec("x", PortType.REAL, "out", "s")
        self.handled: list[tuple[float, tuple[str, ...]]] = []

    def _initialize_component(self, t0: float) -> None:
        self.x = t0

    def _do_step_internal(self, t: float, dt: float) -> None:
        self.x += dt

    def _update_output_states(self, t=None, event_names=None) -> None:
        self.outputs["x"].set(self.x, t)

    def snapshot_state(self) -> float:
        return self.x

    def restore_state(self, snapshot: float, t: float) -> None:
        self.x = snapshot


def clock_system(indicators: dict[str, tuple[Callable[[Clock], float], int]],
                 handler: Callable[[Clock, list[str], float], None] | None = None,
                 t0: float = 0.0) -> tuple[System, Clock]:
    clock = Clock()
    for name, (func, direction) in indicators.items():
        clock.add_event_indicator(name, func=func, direction=direction)
    clock.add_event_handler("tick", handler or (
        lambda comp, names, t: comp.handled.append((t, tuple(names)))))
    system = System("events")
    system.add_component(clock)
    for name in indicators:
        system.add_event_connection(EventConnection("C", name, "C", "tick"))
    system.initialize(t0)
    return system, clock


def crossing(at: float) -> tuple[Callable[[Clock], float], int]:
    return (lambda comp: comp.x - at), 1


def test_two_events_in_one_macro_step_are_handled_once_each_in_order():
    system, clock = clock_system({"a": crossing(0.23), "b": crossing(0.27)})
    result = system.run(0.0, 1.0, 0.1)
    assert [(e.event, e.micro) for e in result.events] == [("a", 0), ("b", 0)]
    np.testing.assert_allclose([e.t for e in result.events], [0.23, 0.27], atol=1e-12)
    assert [names for _, names in clock.handled] == [("a",), ("b",)]
    t, data = result["C"]
    # the grid, plus each event instant before and after handling
    assert len(t) == 11 + 4
    assert np.all(np.diff(t) >= 0)
    np.testing.assert_allclose(data["x"], t, atol=1e-12)


def test_simultaneous_events_are_one_handling_round():
    system, clock = clock_system({"a": crossing(0.55), "b": ((lambda c: 2 * (c.x - 0.55)), 1)})
    result = system.run(0.0, 1.0, 0.1)
    assert [e.event for e in result.events] == ["a", "b"]
    assert result.events[0].t == result.events[1].t == pytest.approx(0.55, abs=1e-12)
    assert clock.handled == [(pytest.approx(0.55, abs=1e-12), ("a", "b"))]
    events = system.history.get_all_event_histories()
    assert events[("C", "a")][0].micro == events[("C", "b")][0].micro == 0


def test_event_exactly_on_a_grid_point_is_handled_once():
    system, clock = clock_system({"a": crossing(0.5)})
    result = system.run(0.0, 1.0, 0.1)
    assert [(e.t, e.event) for e in result.events] == [(pytest.approx(0.5, abs=1e-12), "a")]
    assert len(clock.handled) == 1
    t, _ = result["C"]
    assert np.count_nonzero(np.isclose(t, 0.5, atol=1e-12)) == 2  # before and after handling


def test_event_at_the_final_time_is_handled_once():
    system, clock = clock_system({"a": crossing(1.0)})
    result = system.run(0.0, 1.0, 0.1)
    assert [e.t for e in result.events] == [pytest.approx(1.0, abs=1e-12)]
    assert len(clock.handled) == 1


def test_event_at_t0_is_handled_once():
    # falling indicator that starts exactly on zero: the crossing happens at t0
    system, clock = clock_system({"a": ((lambda c: -c.x), -1)})
    result = system.run(0.0, 1.0, 0.1)
    assert [(e.t, e.event) for e in result.events] == [(0.0, "a")]
    assert clock.handled == [(0.0, ("a",))]


def test_a_rising_indicator_does_not_fire_on_its_way_down():
    system, clock = clock_system({"a": ((lambda c: 0.5 - c.x), 1)})
    assert system.run(0.0, 1.0, 0.1).events == []
    assert clock.handled == []


def test_indicator_that_raises_names_component_event_and_time():
    def fragile(comp: Clock) -> float:
        if comp.x > 0.42:
            raise ValueError("sensor broke")
        return comp.x - 0.9

    system, _ = clock_system({"probe": (fragile, 1)})
    with pytest.raises(SimulationError, match=r"C: event indicator 'probe' raised "
                                              r"ValueError: sensor broke at t=0\.5") as info:
        system.run(0.0, 1.0, 0.1)
    assert info.value.component == "C"
    assert info.value.time == pytest.approx(0.5)
    assert isinstance(info.value.__cause__, ValueError)
    t, _ = system.get_history()["C"]
    np.testing.assert_allclose(t, [0.0, 0.1, 0.2, 0.3, 0.4], atol=1e-12)


def test_handler_that_raises_names_component_event_and_time():
    def clumsy(comp: Clock, names: list[str], t: float) -> None:
        raise RuntimeError("handler failed")

    system, _ = clock_system({"a": crossing(0.35)}, handler=clumsy)
    with pytest.raises(SimulationError, match=r"C: event handler for a raised RuntimeError: "
                                              r"handler failed at t=0\.35") as info:
        system.run(0.0, 1.0, 0.1)
    assert info.value.time == pytest.approx(0.35, abs=1e-12)
    t, _ = system.get_history()["C"]
    assert t[-1] == pytest.approx(0.35, abs=1e-12)  # recorded up to the instant that failed
    assert len(t) >= 4


def test_record_internal_steps_adds_the_localization_trials():
    plain, _ = clock_system({"a": crossing(0.2345)})
    n_plain = len(plain.run(0.0, 1.0, 0.1)["C"][0])
    detailed, _ = clock_system({"a": crossing(0.2345)})
    detailed.algorithm.record_internal_steps = True
    detailed.algorithm.method = "bisection"
    result = detailed.run(0.0, 1.0, 0.1)
    assert len(result["C"][0]) > n_plain
    assert result.statistics.localization_iterations >= 20


def test_result_tables_of_a_hybrid_run(tmp_path):
    system, _ = clock_system({"a": crossing(0.25)})
    result = system.run(0.0, 0.5, 0.1)
    wide = result.to_dataframe("C")
    assert list(wide.columns) == ["time", "micro", "x", "a"]
    assert len(wide) == 6 + 2
    # the event instant has two rows, before and after handling; the EVENT output is true after
    assert wide["time"].tolist().count(0.25) == 2
    assert wide.loc[wide["a"], "time"].tolist() == [0.25]
    assert result.micro[wide.index[wide["a"]]].tolist() == [1]
    assert wide.loc[wide["time"] == 0.25, "micro"].tolist() == [0, 1]
    long = result.to_dataframe()
    assert list(long.columns) == ["component", "port", "time", "micro", "value", "unit"]
    assert long["port"].tolist() == ["x"] * 8 + ["a"] * 8
    lines = result.to_csv(tmp_path / "run.csv").read_text().splitlines()
    assert lines[0] == "component,port,time,micro,value,unit" and len(lines) == 1 + 16
    assert lines[-8:].count("C,a,0.25,1,True,") == 1


def test_keyboard_interrupt_in_a_handler_stays_an_interrupt():
    def interrupted(comp: Clock, names: list[str], t: float) -> None:
        raise KeyboardInterrupt

    system, _ = clock_system({"a": crossing(0.35)}, handler=interrupted)
    with pytest.raises(KeyboardInterrupt):
        system.run(0.0, 1.0, 0.1)
