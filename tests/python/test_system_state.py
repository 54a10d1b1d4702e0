"""The whole system's state from Python: System.save_state, restore_state, SystemState.to_bytes
and System.state_from_bytes on the seed wall pendulum (Euler, its Python wall handler)."""

from __future__ import annotations

import gc

import numpy as np
import pendulum_wall
import pytest
from fixture_fmus import fmu_path
from syssimx import CoSimComponent, FMUComponent, PortSpec, PortType, StateError, System, fmus

DT = 0.05
SAVED_AT = 0.3
STOP = 1.0


def _after(result, start: int) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """The pendulum's samples from index `start` on."""
    t, values = result["P"]
    return t[start:], {port: v[start:] for port, v in values.items()}


def _events(result, start: int) -> list[tuple[str, float, int]]:
    return [(e.event, e.t, e.micro) for e in list(result.events)[start:]]


def _assert_same(first: tuple[np.ndarray, dict[str, np.ndarray]],
                 again: tuple[np.ndarray, dict[str, np.ndarray]]) -> None:
    assert first[0].tobytes() == again[0].tobytes()
    assert first[1].keys() == again[1].keys()
    for port in first[1]:
        assert first[1][port].tobytes() == again[1][port].tobytes(), port


def _run_to_save_point() -> tuple[System, int, int]:
    """The seed system run to SAVED_AT: it, its sample count and its event count there."""
    system, _ = pendulum_wall.build("euler")
    before = system.run(0.0, SAVED_AT, DT)
    return system, len(before["P"][0]), len(before.events)


def test_a_restored_system_repeats_its_samples_and_events_to_the_bit():
    system, saved_samples, saved_events = _run_to_save_point()
    state = system.save_state()
    first = system.run(SAVED_AT, STOP, DT)
    samples, events = len(first["P"][0]), len(first.events)
    assert _events(first, saved_events), "the wall is hit between the save and the stop"

    system.restore_state(state)
    assert system.t == SAVED_AT
    assert system.termination is None
    again = system.run(SAVED_AT, STOP, DT)  # the history goes on: the repeat is appended

    _assert_same(_after(first, saved_samples), _after(again, samples))
    assert _events(again, events) == _events(first, saved_events)
    state.close()
    assert state.closed


def test_a_state_in_bytes_continues_a_freshly_built_identical_system():
    system, saved_samples, saved_events = _run_to_save_point()
    data = system.save_state().to_bytes()
    first = system.run(SAVED_AT, STOP, DT)

    fresh, _ = pendulum_wall.build("euler")
    fresh.restore_state(fresh.state_from_bytes(data))
    assert fresh.t == SAVED_AT
    again = fresh.run(SAVED_AT, STOP, DT)
    start = len(again["P"][0]) - (len(first["P"][0]) - saved_samples)

    _assert_same(_after(first, saved_samples), _after(again, start))
    assert _events(again, 0) == _events(first, saved_events)


def test_a_restore_takes_back_a_termination_that_came_after_the_save():
    ramp = FMUComponent("Ramp", fmu_path("terminating"))
    ramp.set_parameters(stop_time=1.0)
    system = System("ramp")
    system.add_component(ramp)
    system.initialize(0.0)
    system.run(0.0, 0.5, 0.25)
    state = system.save_state()
    stopped = system.run(0.5, 2.0, 0.25)
    assert stopped.termination is not None and system.termination is not None

    system.restore_state(state)
    assert system.termination is None
    assert system.t == 0.5
    again = system.run(0.5, 0.75, 0.25)  # a terminated system would refuse to run
    assert again.termination is None
    assert ramp.t == 0.75


def test_a_state_is_freed_when_collected_after_its_system_is_gone():
    system, _, _ = _run_to_save_point()
    state = system.save_state()
    del system
    gc.collect()
    assert state.to_bytes()  # the state keeps the engine system it belongs to
    del state
    gc.collect()


def test_a_state_of_another_system_is_refused():
    system, _, _ = _run_to_save_point()
    other, _ = pendulum_wall.build("euler")
    with pytest.raises(StateError, match="another engine system"):
        other.restore_state(system.save_state())


def test_bytes_are_no_state_to_restore():
    system, _, _ = _run_to_save_point()
    with pytest.raises(StateError, match="state_from_bytes"):
        system.restore_state(system.save_state().to_bytes())


def test_a_closed_state_is_refused():
    system, _, _ = _run_to_save_point()
    state = system.save_state()
    state.close()
    with pytest.raises(StateError, match="closed"):
        system.restore_state(state)
    with pytest.raises(StateError, match="closed"):
        state.to_bytes()


def test_bytes_that_are_no_state_of_the_system_are_refused():
    system, _, _ = _run_to_save_point()
    data = system.save_state().to_bytes()
    for wrong in (b"not a state", data[:len(data) // 2]):
        with pytest.raises(StateError):
            system.state_from_bytes(wrong)


class _Counter(CoSimComponent):
    """A Python component: its state lives in Python, out of the engine's reach."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.output_specs["n"] = PortSpec("n", PortType.INT, "out")

    def _initialize_component(self, t0: float) -> None:
        self.n = 0

    def _do_step_internal(self, t: float, dt: float) -> None:
        self.n += 1

    def _update_output_states(self, t=None, event_names=None) -> None:
        self.outputs["n"].set(self.n, t)


def test_a_system_with_a_python_component_names_it():
    system = System("pendulum and counter")
    system.add_component(FMUComponent("P", fmus.path("pendulum_euler")))
    system.add_component(_Counter("counter"))
    system.initialize(0.0)
    with pytest.raises(StateError, match="counter") as raised:
        system.save_state()
    assert raised.value.component == "counter"


def test_a_state_before_initialize_is_refused():
    system = System("empty")
    system.add_component(_Counter("counter"))
    with pytest.raises(StateError, match="initialize"):
        system.save_state()

