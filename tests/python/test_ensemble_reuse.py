"""A worker keeps its System from one member of an ensemble to the next (reused_system.py):
every member's result is bit-identical to the same member on a freshly built System, also
after a failed member, after a handler that changed a parameter for good, and with a
component class of the user's (those two are built anew). Members run here, in process,
exactly as a worker runs them."""

from __future__ import annotations

from collections.abc import Callable, Iterator

import coupled_pendulums
import numpy as np
import pendulum_wall
import pytest
from fixture_fmus import fmu_path
from syssimx import (
    Connection,
    CoSimComponent,
    FMUComponent,
    JacobiAlgorithm,
    MultiComponent,
    PortSpec,
    PortType,
    Reinitialize,
    System,
    fmus,
)
from syssimx.ensemble import MemberResult, MemberTask, parameter_sets, run_member
from syssimx.ensemble import member as member_module
from syssimx.ensemble.reused_system import ReusedSystem
from syssimx.system.member_runs import EngineMembers


class CountedBuild:
    """A system function that counts the Systems it built."""

    def __init__(self, build: Callable[[], System]) -> None:
        self.build, self.built = build, 0

    def __call__(self) -> System:
        self.built += 1
        return self.build()


@pytest.fixture(autouse=True)
def own_reused_system(monkeypatch) -> Iterator[None]:
    """A kept System of this test's own, dropped after it (not left in the test process)."""
    monkeypatch.setattr(member_module, "reused_system", ReusedSystem())
    yield


def run_all(build: Callable[[], System], parameters: dict[str, list], tf: float, dt: float,
            ensemble: str | None) -> list[MemberResult]:
    return [run_member(build, MemberTask(index, values, 0.0, tf, dt, ensemble=ensemble))
            for index, values in enumerate(parameter_sets(parameters, mode="zip"))]


def assert_bit_identical(reused: list[MemberResult], fresh: list[MemberResult]) -> None:
    for again, alone in zip(reused, fresh, strict=True):
        where = f"member {alone.index}"
        assert (again.status, again.error, again.termination) == \
            (alone.status, alone.error, alone.termination), where
        assert np.array_equal(again.time, alone.time), where
        assert np.array_equal(again.micro, alone.micro), where
        assert again.outputs.keys() == alone.outputs.keys(), where
        for name, values in alone.outputs.items():
            assert np.array_equal(again.outputs[name], values), (where, name)
        assert again.events == alone.events, where
        assert again.statistics == alone.statistics, where


def seed_pendulum() -> System:
    return pendulum_wall.build("cvode")[0]


def restarting_seed() -> System:
    """The seed scenario with its declarative handler: the engine restarts the FMU at the
    wall."""
    return pendulum_wall.build("cvode", handler=Reinitialize(theta0="theta",
                                                             omega0="-omega"))[0]


def members_run_in_the_engine(monkeypatch) -> list[list[float]]:
    """The parameter values of each member the engine runs from now on, in order."""
    engine_members: list[list[float]] = []
    start = EngineMembers.start
    monkeypatch.setattr(EngineMembers, "start",
                        lambda self, *args: engine_members.append(args[0]) or start(self, *args))
    return engine_members


def test_seed_sweep_on_one_system_is_bit_identical_to_fresh_systems() -> None:
    thetas = {"P.theta0": [0.2, 0.5, -0.3, 0.65, 0.5]}  # -0.3 has no wall hit before 1 s
    fresh_build, reused_build = CountedBuild(seed_pendulum), CountedBuild(seed_pendulum)
    fresh = run_all(fresh_build, thetas, 1.0, 0.05, ensemble=None)
    reused = run_all(reused_build, thetas, 1.0, 0.05, ensemble="seed")
    assert [len(m.events) for m in fresh] == [1, 1, 0, 1, 1]
    assert_bit_identical(reused, fresh)
    assert (fresh_build.built, reused_build.built) == (5, 1)


def test_members_after_the_first_run_in_the_engine_bit_identical(monkeypatch) -> None:
    """The seed scenario with its declarative handler (the engine restarts the FMU at the
    wall): every member after the first is one engine call, with the same samples, events and
    statistics as on fresh Systems."""
    engine_members = members_run_in_the_engine(monkeypatch)
    values = {"P.theta0": [0.2, 0.5, -0.3, 0.65], "P.L": [1.0, 0.8, 1.2, 1.5]}
    reused = run_all(restarting_seed, values, 1.0, 0.05, ensemble="declarative")
    assert engine_members == [[0.5, 0.8], [-0.3, 1.2], [0.65, 1.5]]
    fresh = run_all(restarting_seed, values, 1.0, 0.05, ensemble=None)
    assert [len(m.events) for m in fresh] == [1, 1, 1, 2]
    assert_bit_identical(reused, fresh)


def test_a_value_set_parameters_refuses_fails_its_member_on_a_kept_system_too(monkeypatch
                                                                           ) -> None:
    """A bool for a Real parameter: set_parameters refuses it, so the engine does not write it
    either; the members around it run in the engine."""
    engine_members = members_run_in_the_engine(monkeypatch)
    values = {"P.theta0": [0.3, 0.35, True, 0.4, 0.45]}
    reused = run_all(restarting_seed, values, 1.0, 0.05, ensemble="refused")
    assert engine_members == [[0.35], [0.45]]
    assert [m.status for m in reused] == ["ok", "ok", "failed", "ok", "ok"]
    assert_bit_identical(reused, run_all(restarting_seed, values, 1.0, 0.05, ensemble=None))


def test_coupled_pendulums_varying_two_components_on_one_system() -> None:
    def build() -> System:
        return coupled_pendulums.build(JacobiAlgorithm(), rtol=1e-8)

    values = {"P1.theta0": [0.2, 0.4, 0.3], "Spring.k": [90.0, 110.0, 100.0]}
    reused_build = CountedBuild(build)
    reused = run_all(reused_build, values, 0.5, 0.01, ensemble="coupled")
    assert_bit_identical(reused, run_all(build, values, 0.5, 0.01, ensemble=None))
    assert reused_build.built == 1


def failing_system() -> System:
    """The failing FMU (y = u) fed a constant input: it fails after fail_time as `failure`
    says (0 error, 1 fatal, 2 discard, 3 read failure, 4 NaN, which stops the run where it
    reaches an input: y feeds a gain)."""
    failing = FMUComponent("F", fmu_path("failing"))
    failing.set_inputs({"u": 2.0})
    system = System("failing")
    system.add_component(failing)
    system.add_component(FMUComponent("G", fmus.path("gain")))
    system.add_connection(Connection("F", "y", "G", "u", convert_units=False))
    return system


def test_after_each_failed_member_the_next_gets_a_fresh_system() -> None:
    # fmi2Fatal (failure 1) leaves an FMU that refuses every call: its System is not kept
    values = {"F.failure": [0, 0, 1, 0, 2, 0, 3, 0, 4, 0],
              "F.fail_time": [2.0, 0.5, 0.5, 2.0, 0.5, 2.0, 0.5, 2.0, 0.5, 2.0]}
    reused_build = CountedBuild(failing_system)
    reused = run_all(reused_build, values, 1.0, 0.1, ensemble="failing")
    fresh = run_all(failing_system, values, 1.0, 0.1, ensemble=None)
    assert [m.status for m in reused] == ["ok", "failed", "failed", "ok", "failed", "ok",
                                          "failed", "ok", "failed", "ok"]
    assert "a deliberate fatal failure" in reused[2].error
    assert_bit_identical(reused, fresh)
    # the first member's System served the second; each failure made the next build anew
    assert reused_build.built == 1 + 5


def bounce_for_good(component: FMUComponent, event_names: list[str], t: float) -> None:
    """pendulum_wall's bounce, and omega0 changed for good (the next initialize would start
    from it)."""
    pendulum_wall.bounce(component, event_names, t)
    component.set_parameters(omega0=0.25)


def pendulum_changed_by_its_handler() -> System:
    system, pendulum = pendulum_wall.build("cvode")
    pendulum.event_handlers["omega_invert"] = [bounce_for_good]
    return system


class StepCounter(CoSimComponent):
    """Outputs the steps it took since it was made: state of its own that initialize does
    not reset, so a reused System would count on from the previous member."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.output_specs["steps"] = PortSpec("steps", PortType.REAL, "out")
        self.steps = 0

    def _do_step_internal(self, t: float, dt: float) -> None:
        self.steps += 1

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        self.outputs["steps"].set(float(self.steps), t)


def pendulum_and(counter: CoSimComponent) -> System:
    system = System("a pendulum and a step counter")
    system.add_component(FMUComponent("P", fmus.path("pendulum_cvode")))
    system.add_component(counter)
    return system


def pendulum_and_a_counter() -> System:
    return pendulum_and(StepCounter("C"))


def pendulum_and_a_counter_inside_a_multicomponent() -> System:
    return pendulum_and(MultiComponent("C", {"counting": StepCounter("inner")}, "counting"))


@pytest.mark.parametrize(("build", "built"), [
    (pendulum_changed_by_its_handler, [1, 2, 3, 3]),  # the member without a hit is kept
    (pendulum_and_a_counter, [1, 2, 3, 4]),
    (pendulum_and_a_counter_inside_a_multicomponent, [1, 2, 3, 4]),
])
def test_a_system_its_run_changed_or_of_a_users_class_is_built_anew(build, built) -> None:
    thetas = {"P.theta0": [0.5, 0.3, -0.3, 0.4]}
    counted = CountedBuild(build)
    reused, builds_so_far = [], []
    for index, values in enumerate(parameter_sets(thetas)):
        reused.append(run_member(counted, MemberTask(index, values, 0.0, 1.0, 0.05,
                                                     ensemble="x")))
        builds_so_far.append(counted.built)
    assert_bit_identical(reused, run_all(build, thetas, 1.0, 0.05, ensemble=None))
    assert builds_so_far == built
