"""An output clock of an FMU that cannot return early: level_detector_step_end_fmi3 (a fixture
built from the toolchain's LevelDetector, mightReturnEarlyFromDoStep false) empties its tank
inside the step at the threshold and reports the tick of `full` at the end of that step. Where
every component can roll back the hybrid algorithm brackets the tick by bisection within
tol_time, and the connected tick_counter_fmi3 ticks there; without rollback the tick reaches it
at the end of the step that held it.

With inflow 1.3 and threshold 0.3 the tank is full at k 0.3 / 1.3 (level0 = 0), off every
communication point of the steps 0.1 and 0.25."""

from __future__ import annotations

import zipfile

import pytest
from bouncing_pendulum import WALL_HIT, Passive, add_bouncing_pendulum
from fixture_fmus import fixture_dir
from fmpy.validation import validate_fmu
from syssimx import (
    Connection,
    FMUComponent,
    GaussSeidelAlgorithm,
    HybridAlgorithm,
    System,
    fmus,
)

TANK = "level_detector_step_end_fmi3"
COUNTER = "tick_counter_fmi3"
INFLOW, THRESHOLD = 1.3, 0.3
FULL_TIMES = [k * THRESHOLD / INFLOW for k in (1, 2, 3, 4)]
TOL_TIME = 1e-9


def tank_path() -> str:
    return str(fixture_dir() / f"{TANK}.fmu")


def tank_and_counter(threads: int = 1, roll_back: bool = True) -> System:
    system = System("tank without early return and counter")
    tank = FMUComponent("Tank", tank_path())
    tank.set_parameters(threshold=THRESHOLD)
    tank.set_inputs({"inflow": INFLOW})
    system.add_component(tank)
    system.add_component(FMUComponent("Counter", fmus.path(COUNTER)))
    system.add_connection(Connection("Tank", "level", "Counter", "signal"))
    system.add_clock_connection("Tank.full", "Counter.tick")
    if not roll_back:
        system.add_component(Passive("Passive"))
    system.set_algorithm(HybridAlgorithm(tol_time=TOL_TIME,
                                         coupling=GaussSeidelAlgorithm(threads=threads)))
    return system


def counter_ticks(dt: float, threads: int = 1, roll_back: bool = True) -> list[float]:
    system = tank_and_counter(threads, roll_back)
    system.initialize(0.0)
    return [e.t for e in system.run(0.0, 1.0, dt).events if e.event == "tick"]


def test_the_tank_declares_that_it_never_returns_early_and_validates() -> None:
    with zipfile.ZipFile(tank_path()) as fmu:
        description = fmu.read("modelDescription.xml").decode()
    assert 'mightReturnEarlyFromDoStep="false"' in description
    assert "canReturnEarlyAfterIntermediateUpdate" not in description
    assert validate_fmu(tank_path()) == []


def test_without_rollback_the_tick_comes_at_the_end_of_the_step_that_held_it() -> None:
    assert counter_ticks(0.25, roll_back=False) == pytest.approx([0.25, 0.5, 0.75, 1.0])


@pytest.mark.parametrize("threads", [1, 2])
@pytest.mark.parametrize("dt", [0.1, 0.25])
def test_a_tick_reported_at_a_step_end_is_bisected_to_its_own_time(dt: float,
                                                                   threads: int) -> None:
    system = tank_and_counter(threads)
    system.initialize(0.0)
    result = system.run(0.0, 1.0, dt)
    ticks = [e.t for e in result.events if e.event == "tick"]
    for tick, full in zip(ticks, FULL_TIMES, strict=True):
        # the bracket's far end: at or after the tank's time, within tol_time
        assert -1e-15 <= tick - full <= TOL_TIME
    # the last tick sampled the level the tank had just after emptying
    assert system.components["Counter"].outputs["sampled"].value == pytest.approx(
        0.0, abs=INFLOW * TOL_TIME)
    # each bisection trial is a localization iteration stepped again from a rollback
    assert result.statistics.localization_iterations >= 4 * 20
    assert result.statistics.state_restores >= result.statistics.localization_iterations
    assert counter_ticks(dt, threads) == ticks


@pytest.mark.parametrize("dt", [0.1, 0.25])
def test_bisected_ticks_leave_the_seed_pendulum_s_wall_hit_where_it_was(dt: float) -> None:
    system = tank_and_counter()
    add_bouncing_pendulum(system)
    system.initialize(0.0)
    events = system.run(0.0, 1.0, dt).events
    hits = [e.t for e in events if e.event == "wall_hit"]
    ticks = [e.t for e in events if e.event == "tick"]
    assert hits[0] == pytest.approx(WALL_HIT, abs=1e-9)
    assert ticks == pytest.approx(FULL_TIMES, abs=TOL_TIME)
