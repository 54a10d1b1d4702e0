"""The fixed cost of a run: a System initialized again keeps its engine plan while its
structure is unchanged and resets its FMU instances (fmi2Reset) instead of instantiating them
again; every run on it is bit-identical to the same run on a freshly built System. A change of
structure compiles a new plan; what initialize sets (input starts, output_interval) never
carries over from an earlier initialize; `System.run` touches no component, yet each reads the
System's time after it."""

from __future__ import annotations

import coupled_pendulums
import numpy as np
import pendulum_wall
import pytest
from syssimx import (
    Connection,
    FMUComponent,
    GaussSeidelAlgorithm,
    SimulationResult,
    StepControl,
    System,
    fmus,
)
from syssimx.errors import ConfigurationError


def _seed_run(system: System, theta0: float) -> tuple[list[float], np.ndarray]:
    system.components["P"].set_parameters(theta0=theta0)
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.05)
    return [e.t for e in result.events], result["P"][1]["theta"].copy()


@pytest.mark.parametrize("solver", ["cvode", "euler"])
def test_reinitialized_system_keeps_its_plan_and_instance_and_its_numbers(solver: str) -> None:
    """The seed scenario three times on one System, against each on a fresh System: the same
    events and samples to the bit, one plan, one FMU instance (reset three times, plus once
    by the handler per event)."""
    system, pendulum = pendulum_wall.build(solver)
    plan = system._plan
    reused = [_seed_run(system, theta0) for theta0 in (0.5, 0.3, 0.5)]
    assert system._plan is plan
    counters = pendulum.instance.counters()
    assert counters["instantiate"] == 1
    events = sum(len(times) for times, _ in reused)
    assert counters["reset"] == 3 + events  # each initialize, each handler's reinitialize
    for (times, theta), theta0 in zip(reused, (0.5, 0.3, 0.5), strict=True):
        fresh_system, fresh = pendulum_wall.build(solver)
        fresh_system.reset()  # no plan, no instance: the next initialize makes both anew
        fresh_times, fresh_theta = _seed_run(fresh_system, theta0)
        assert fresh.instance.counters()["instantiate"] == 2
        assert times == fresh_times and np.array_equal(theta, fresh_theta)
        fresh.free()
    assert reused[0][0] == reused[2][0] and np.array_equal(reused[0][1], reused[2][1])
    assert abs(reused[0][0][0] - pendulum_wall.QUARTER_PERIOD) < (
        1e-9 if solver == "cvode" else 3e-6)
    pendulum.free()


def test_changed_structure_compiles_a_new_plan() -> None:
    gain = FMUComponent("G", fmus.path("gain"))
    gain.set_inputs({"u": 2.0})
    gain.set_parameters(k=1.5)
    system = System("grows")
    system.add_component(gain)
    system.initialize(0.0)
    first = system._plan
    system.initialize(0.0)
    assert system._plan is first
    second = FMUComponent("H", fmus.path("gain"))
    second.set_parameters(k=-2.0)
    system.add_component(second)
    system.add_connection(Connection("G", "y", "H", "u"))
    system.initialize(0.0)
    assert system._plan is not first
    result = system.run(0.0, 0.2, 0.1)
    assert result["H"][1]["y"][1:].tolist() == [-6.0] * 2  # (t0 holds the gain's start)


def test_a_reused_plan_takes_new_input_starts_and_forgets_earlier_options() -> None:
    """set_inputs between initializes reaches the engine; an output_interval given to one
    initialize is not kept by the next (the engine's default again: every point)."""
    source = FMUComponent("S", fmus.path("gain"))
    sink = FMUComponent("K", fmus.path("gain"))
    system = System("starts")
    for component in (source, sink):
        system.add_component(component)
    system.add_connection(Connection("S", "y", "K", "u"))
    source.set_parameters(k=1.5)
    sink.set_parameters(k=-2.0)
    source.set_inputs({"u": 1.0})
    system.initialize(0.0, output_interval=2)
    first = system.run(0.0, 0.4, 0.1)
    assert first["K"][0].tolist() == [0.0, 0.2, 0.4]
    plan = system._plan
    source.set_inputs({"u": 3.0})
    system.initialize(0.0)
    assert system._plan is plan
    second = system.run(0.0, 0.4, 0.1)
    assert second["K"][0].size == 5
    assert second["K"][1]["y"][1:].tolist() == [-9.0] * 4
    assert second["S"][1]["y"].tolist() == [4.5] * 5


def test_run_leaves_components_alone_but_their_time_follows() -> None:
    gains = [FMUComponent(f"G{i}", fmus.path("gain")) for i in range(3)]
    system = System("time")
    for gain in gains:
        system.add_component(gain)
    system.initialize(0.0)
    system.run(0.0, 0.3, 0.1)
    assert [g.t for g in gains] == [pytest.approx(0.3)] * 3
    gains[0].t = 7.0  # a time the component sets itself wins until the next run
    assert gains[0].t == 7.0
    system.run(system.t, 0.5, 0.1)
    assert [g.t for g in gains] == [pytest.approx(0.5)] * 3


def test_a_component_initialized_elsewhere_stops_the_run_and_a_new_plan_is_made() -> None:
    gain = FMUComponent("G", fmus.path("gain"))
    first, second = System("first"), System("second")
    first.add_component(gain)
    second.add_component(gain)
    first.initialize(0.0)
    plan = first._plan
    second.initialize(0.0)
    with pytest.raises(ConfigurationError, match="'G' was initialized elsewhere"):
        first.run(0.0, 0.1, 0.1)
    first.initialize(0.0)
    assert first._plan is not plan
    assert first.run(0.0, 0.1, 0.1)["G"][0].size == 2


def _everything(result: SimulationResult) -> tuple[object, ...]:
    """What a result holds: its samples, micro steps, events and statistics."""
    t, ports = result["P"]
    return (t.tolist(), {name: values.tolist() for name, values in ports.items()},
            result.micro.tolist(), [(e.t, e.micro, e.component, e.event) for e in result.events],
            result.statistics)


def test_a_result_first_read_after_later_runs_holds_its_own_run() -> None:
    """A result makes its arrays, micro steps and statistics only when asked for: asked for
    after the same System ran another member and was initialized again, they are still those
    of its own run, to the bit those of the run on a fresh System."""
    system, pendulum = pendulum_wall.build("euler")
    first = _run_member(system, 0.5)
    second = _run_member(system, 0.3)
    system.components["P"].set_parameters(theta0=0.4)
    system.initialize(0.0)  # a third start, not run
    for result, theta0 in ((first, 0.5), (second, 0.3)):
        fresh_system, fresh = pendulum_wall.build("euler")
        expected = _everything(_run_member(fresh_system, theta0))
        assert _everything(result) == expected
        assert result.statistics.events == len(result.events) >= 1
        fresh.free()
    pendulum.free()


def _run_member(system: System, theta0: float) -> SimulationResult:
    system.components["P"].set_parameters(theta0=theta0)
    system.initialize(0.0)
    return system.run(0.0, 1.0, 0.05)


def test_what_one_run_or_initialize_sets_is_not_kept_by_the_next() -> None:
    """output_interval of a run and of an initialize hold for that call only, also where the
    reused plan skips setting what the engine holds already."""
    gain = FMUComponent("G", fmus.path("gain"))
    gain.set_inputs({"u": 1.0})
    system = System("settings")
    system.add_component(gain)
    system.initialize(0.0, output_interval=2)
    assert system.run(0.0, 0.4, 0.1)["G"][0].tolist() == pytest.approx([0.0, 0.2, 0.4])
    assert system.run(0.4, 0.8, 0.1, output_interval=0.4)["G"][0].tolist() == pytest.approx(
        [0.0, 0.2, 0.4, 0.8])
    assert system.run(0.8, 1.2, 0.1)["G"][0].tolist() == pytest.approx(
        [0.0, 0.2, 0.4, 0.8, 1.0, 1.2])
    plan = system._plan
    system.initialize(0.0)
    assert system._plan is plan
    assert system.run(0.0, 0.3, 0.1)["G"][0].tolist() == pytest.approx([0.0, 0.1, 0.2, 0.3])
    assert system.run(0.3, 0.5, 0.1, output_interval=0.2)["G"][0].tolist() == pytest.approx(
        [0.0, 0.1, 0.2, 0.3, 0.5])
    assert system.run(0.5, 0.7, 0.1)["G"][0].size == 7


def test_options_changed_in_place_reach_a_reused_plan() -> None:
    """A StepControl changed in place between two initializes of one System: the run is the
    run of a fresh System with the new tolerance, not the old one."""
    control = StepControl(rtol=1e-3, atol=1e-3)
    system = coupled_pendulums.build(GaussSeidelAlgorithm(input_order=1, step_control=control))
    system.initialize(0.0)
    loose = system.run(0.0, 1.0, 0.1).statistics
    control.rtol = control.atol = 1e-6
    system.initialize(0.0)
    tight = system.run(0.0, 1.0, 0.1)
    fresh = coupled_pendulums.build(GaussSeidelAlgorithm(
        input_order=1, step_control=StepControl(rtol=1e-6, atol=1e-6)))
    fresh.initialize(0.0)
    expected = fresh.run(0.0, 1.0, 0.1)
    assert tight.statistics == expected.statistics
    assert tight.statistics.accepted_steps > loose.accepted_steps
    assert np.array_equal(tight["P1"][1]["theta"], expected["P1"][1]["theta"])
