"""Members run by the engine (System.run_members): one engine call per member on a System
initialized once gives the histories of the loop set_parameters, initialize, run, bit for bit."""

from __future__ import annotations

import os
import signal
import threading
import time

import numpy as np
import pytest
from fixture_fmus import fmu_path
from syssimx import (
    Connection,
    EventConnection,
    FMUComponent,
    HybridAlgorithm,
    Reinitialize,
    System,
    fmus,
)
from syssimx.errors import ConfigurationError, RunInterrupted
from syssimx.system.member_runs import MemberSamples, engine_runs_members, split_member_names

T0, TF, DT = 0.0, 1.0, 0.05


def _pendulum_system(fmu: str) -> System:
    system = System("members")
    system.add_component(FMUComponent("P", fmus.path(fmu)))
    return system


def _wall_system(solver: str) -> System:
    """The seed scenario: the pendulum against a wall, its restart run by the engine."""
    pendulum = FMUComponent("P", fmus.path(f"pendulum_{solver}"))
    pendulum.set_parameters(theta0=0.5, omega0=0.0)
    pendulum.add_event_indicator("wall_hit", variable="theta", direction=-1)
    pendulum.add_event_handler("omega_invert", Reinitialize(theta0="theta", omega0="-omega"))
    system = System("wall")
    system.add_component(pendulum)
    system.add_event_connection(EventConnection("P", "wall_hit", "P", "omega_invert"))
    system.set_algorithm(HybridAlgorithm(tol_time=1e-9, tol_value=1e-9))
    return system


def _loop(system: System, values: dict[str, list[float]]) -> list[MemberSamples]:
    """The members as a user's loop runs them on one System."""
    samples = []
    for k in range(len(next(iter(values.values())))):
        for name, column in values.items():
            component, parameter = name.split(".")
            system.components[component].set_parameters(**{parameter: column[k]})
        system.initialize(T0)
        result = system.run(T0, TF, DT)
        t, outputs = result["P"]
        events = tuple((e.t, e.micro, f"{e.component}.{e.event}") for e in result.events)
        samples.append(MemberSamples(np.array(t), np.array(result.micro, dtype=np.int64),
                                     {f"P.{port}": np.array(series)
                                      for port, series in outputs.items()}, events))
    return samples


def _assert_identical(engine: list[MemberSamples], loop: list[MemberSamples]) -> None:
    assert len(engine) == len(loop)
    for ours, theirs in zip(engine, loop, strict=True):
        assert np.array_equal(ours.time, theirs.time)
        assert np.array_equal(ours.micro, theirs.micro)
        assert ours.outputs.keys() == theirs.outputs.keys()
        for name, series in theirs.outputs.items():
            assert np.array_equal(ours.outputs[name], series), name
        assert ours.events == theirs.events


@pytest.mark.parametrize("fmu", ["pendulum_euler", "pendulum_cvode", "pendulum_euler_fmi3"])
def test_engine_members_match_the_loop_bit_for_bit(fmu: str) -> None:
    values = {"P.theta0": [0.2, 0.35, 0.5, 0.6], "P.L": [1.0, 0.8, 1.2, 1.1]}
    system = _pendulum_system(fmu)
    assert engine_runs_members(system, split_member_names(system, list(values)))
    engine = system.run_members(values, T0, TF, DT)
    assert len({float(member.outputs["P.theta"][-1]) for member in engine}) == 4
    _assert_identical(engine, _loop(_pendulum_system(fmu), values))


def test_engine_members_restart_with_the_member_values() -> None:
    """The wall's restart writes the member's L again at each hit (a start value of the
    restart), the member's theta0 only at the start (the restart takes theta from the
    outputs)."""
    values = {"P.theta0": [0.5, 0.3, 0.7], "P.L": [1.0, 0.5, 2.0]}
    system = _wall_system("euler")
    assert engine_runs_members(system, split_member_names(system, list(values)))
    engine = system.run_members(values, T0, TF, DT)
    assert all(member.events for member in engine)
    assert len({member.events[0][0] for member in engine}) == 3
    _assert_identical(engine, _loop(_wall_system("euler"), values))


def test_system_is_left_as_the_loop_leaves_it() -> None:
    system = _pendulum_system("pendulum_euler")
    engine = system.run_members({"P.theta0": [0.2, 0.4]}, T0, TF, DT)
    assert system.components["P"].parameters["theta0"] == 0.4
    assert system.t == pytest.approx(TF)
    _t, outputs = system.get_history()["P"]
    assert np.array_equal(outputs["theta"], engine[-1].outputs["P.theta"])
    later = system.run(TF, TF + 2 * DT, DT)["P"][0]  # it goes on from the last member
    assert np.array_equal(later[-3:], [TF, TF + DT, TF + 2 * DT])


def _failing_and_gain() -> System:
    """An FMU with an Integer parameter (failure: 0 never fails) feeding a gain."""
    failing = FMUComponent("F", fmu_path("failing"))
    failing.set_inputs({"u": 2.0})
    system = System("integer parameter")
    system.add_component(failing)
    system.add_component(FMUComponent("G", fmus.path("gain")))
    system.add_connection(Connection("F", "y", "G", "u", convert_units=False))
    return system


def test_an_integer_parameter_is_written_as_set_parameters_writes_it() -> None:
    values = {"F.failure": [0, 0], "F.fail_time": [2.0, 3.0]}
    system = _failing_and_gain()
    assert engine_runs_members(system, split_member_names(system, list(values)))
    engine = system.run_members(values, T0, TF, 0.1)
    loop = []
    reference = _failing_and_gain()
    for failure, fail_time in zip(*values.values(), strict=True):
        reference.components["F"].set_parameters(failure=failure, fail_time=fail_time)
        reference.initialize(T0)
        t, outputs = reference.run(T0, TF, 0.1)["G"]
        loop.append((np.array(t), np.array(outputs["y"])))
    for member, (t, y) in zip(engine, loop, strict=True):
        assert np.array_equal(member.time, t)
        assert np.array_equal(member.outputs["G.y"], y)
    # 0.5 is no Integer: set_parameters refuses it, and so does run_members (no truncation)
    with pytest.raises(ConfigurationError, match="INT"):
        _failing_and_gain().run_members({"F.failure": [0, 0.5, 0]}, T0, TF, 0.1)


MANY_MEMBERS = 200_000  # about half a minute of 20-step members on the engine's one call
SIGNAL_AFTER, STOP_WITHIN = 0.5, 1.0  # seconds, as for a run (test_run_interruptible.py)


@pytest.mark.parametrize("fmu", ["pendulum_euler", "pendulum_euler_fmi3"])
def test_ctrl_c_stops_a_long_table_of_members_with_those_finished(fmu: str):
    """Each member's run is shorter than the monitor's interval, so before, the monitor was
    never called and Ctrl-C waited for the whole table (49 s for 400,000 members)."""
    system = _pendulum_system(fmu)
    theta0 = np.linspace(0.1, 0.5, MANY_MEMBERS)
    timer = threading.Timer(SIGNAL_AFTER, lambda: os.kill(os.getpid(), signal.SIGINT))
    started = time.monotonic()
    timer.start()
    try:
        with pytest.raises(RunInterrupted) as caught:
            system.run_members({"P.theta0": theta0}, T0, TF, DT)
    finally:
        timer.cancel()
    assert time.monotonic() - started < SIGNAL_AFTER + STOP_WITHIN
    partial = caught.value.partial_result
    assert 0 < len(partial) < MANY_MEMBERS
    last = partial[len(partial) - 1]
    alone = _pendulum_system(fmu)
    runs = alone.run_members({"P.theta0": theta0[len(partial) - 1:len(partial)]}, T0, TF, DT)
    np.testing.assert_array_equal(last.outputs["P.theta"], runs[0].outputs["P.theta"])
