"""FMI 3.0 output clocks, triggered input clocks and clock connections in Co-Simulation, with
the toolchain's two clocked FMUs: level_detector_fmi3 (a tank filled at `inflow`, emptied when
its level reaches `threshold`; its output clock `full` ticks there and its clocked output
`count` counts the ticks) and tick_counter_fmi3 (its triggered input clock `tick` counts ticks
into `count`, `last_tick` and the sampled `signal`).

With inflow 1 and threshold 0.3 the tank is full at 0.3, 0.6 and 0.9 (level0 = 0): exact,
since the level is linear in time and the FMU locates its event by linear interpolation."""

from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np
import pytest
from bouncing_pendulum import WALL_HIT, Passive, add_bouncing_pendulum
from fmpy.validation import validate_fmu
from ssp_archive import ssd, write_ssp
from syssimx import (
    Connection,
    CoSimComponent,
    EventConnection,
    FMUComponent,
    GaussSeidelAlgorithm,
    HybridAlgorithm,
    Reinitialize,
    System,
    fmus,
)
from syssimx.errors import ConfigurationError
from syssimx.ssp import load as load_ssp
from syssimx.system.loader import build_system

TANK = "level_detector_fmi3"
COUNTER = "tick_counter_fmi3"
FULL_TIMES = (0.3, 0.6, 0.9)


def tank_and_counter(connect: bool = True) -> System:
    system = System("tank and counter")
    system.add_component(FMUComponent("Tank", fmus.path(TANK)))
    system.add_component(FMUComponent("Counter", fmus.path(COUNTER)))
    system.add_connection(Connection("Tank", "level", "Counter", "signal"))
    if connect:
        system.add_clock_connection("Tank.full", "Counter.tick")
    return system


@pytest.mark.parametrize("stem", [TANK, COUNTER])
def test_fmpy_validates_the_clocked_fmus(stem: str) -> None:
    assert validate_fmu(fmus.path(stem)) == []


def test_the_clocks_are_the_fmus_event_sources_and_clock_inputs() -> None:
    tank, counter = FMUComponent("Tank", fmus.path(TANK)), FMUComponent("C", fmus.path(COUNTER))
    assert (tank.output_clocks, tank.triggered_clocks) == (["full"], [])
    assert (counter.output_clocks, counter.triggered_clocks) == ([], ["tick"])


def test_the_output_clock_ticks_at_the_threshold_and_count_changes_there_only() -> None:
    system = tank_and_counter(connect=False)
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.25)
    full = [e for e in result.events if e.event == "full"]
    assert [e.component for e in full] == ["Tank"] * 3
    assert [e.t for e in full] == pytest.approx(FULL_TIMES, abs=1e-12)
    assert all(e.own and e.micro == 0 for e in full)
    # the FMU's own event at the same instant comes first, then its output clock
    kinds = [(e.t, e.event) for e in result.events]
    assert kinds[:2] == [(full[0].t, "fmu_event"), (full[0].t, "full")]
    t, values = result["Tank"]
    assert list(t) == pytest.approx([0.0, 0.25, 0.5, 0.75, 1.0])
    assert list(values["count"]) == [0, 0, 1, 2, 3]


def test_the_tank_s_samples_equal_fmpy_s() -> None:
    """FMPy 0.3.32 runs the FMU without event mode (its events handled inside doStep, the clock
    unseen): simulate_fmu(level_detector_fmi3.fmu, stop_time=1, output_interval=0.25,
    fmi_type="CoSimulation") gave these level and count samples."""
    fmpy_level = [0.0, 0.25, 0.2, 0.15000000000000002, 0.10000000000000009]
    fmpy_count = [0.0, 0.0, 1.0, 2.0, 3.0]
    system = tank_and_counter(connect=False)
    system.initialize(0.0)
    values = system.run(0.0, 1.0, 0.25)["Tank"][1]
    assert list(values["level"]) == pytest.approx(fmpy_level, abs=1e-12)
    assert list(values["count"]) == fmpy_count


@pytest.mark.parametrize("offset", [-1e-6, 0.0, 1e-6])
def test_count_and_the_connected_tick_just_before_at_and_just_after_each_tick(
        offset: float) -> None:
    """The communication points fall at tick + offset: the clocked outputs of both FMUs hold
    their value before the tick, and have changed at it and after it."""
    system = tank_and_counter()
    system.initialize(0.0)
    start = 0.0
    for k, tick in enumerate(FULL_TIMES):
        system.run(start, tick + offset, tick + offset - start)
        start = tick + offset
        tank, counter = system.components["Tank"], system.components["Counter"]
        expected = k if offset < 0 else k + 1
        assert tank.outputs["count"].value == expected
        assert counter.outputs["count"].value == expected
        if offset >= 0:
            # the connected tick came at the tank's, inside the step or on its end
            assert counter.outputs["last_tick"].raw() == pytest.approx(tick, abs=1e-9)
            # it sampled the level after the tank was emptied there
            assert counter.outputs["sampled"].value == pytest.approx(0.0, abs=1e-12)


TOL_TIME = 1e-9  # the engine's default tol_time


def counter_ticks(dt: float, threads: int = 1,
                  extra: CoSimComponent | None = None) -> tuple[list[float], System]:
    system = tank_and_counter()
    if extra is not None:
        system.add_component(extra)
    system.set_algorithm(GaussSeidelAlgorithm(threads=threads))
    system.initialize(0.0)
    result = system.run(0.0, 1.0, dt)
    return [e.t for e in result.events if e.event == "tick"], system


@pytest.mark.parametrize("threads", [1, 2])
@pytest.mark.parametrize("dt", [0.1, 0.25])
def test_an_output_clock_ticks_the_connected_clock_at_its_own_time(dt: float,
                                                                   threads: int) -> None:
    """The tank returns early from its step at each threshold time: the system steps back and
    on to that time, and the counter ticks there, whatever the communication step."""
    ticks, system = counter_ticks(dt, threads)
    assert ticks == pytest.approx(FULL_TIMES, abs=TOL_TIME)
    counter = system.components["Counter"]
    assert counter.outputs["count"].value == 3
    assert counter.outputs["last_tick"].raw() == pytest.approx(FULL_TIMES[-1], abs=TOL_TIME)
    # the last tick sampled the level of the tank it emptied: 0, not the level at a
    # communication point after it
    assert counter.outputs["sampled"].value == pytest.approx(0.0, abs=1e-12)
    assert counter_ticks(dt, threads)[0] == ticks


def test_without_rollback_a_connected_tick_comes_at_the_next_communication_point() -> None:
    ticks, _ = counter_ticks(0.25, extra=Passive("Passive"))
    assert ticks == [0.5, 0.75, 1.0]


def test_an_indicator_crossing_ticks_a_triggered_clock_at_the_located_time() -> None:
    system = System("wall hits counted")
    add_bouncing_pendulum(system)
    system.add_component(FMUComponent("Counter", fmus.path(COUNTER)))
    system.add_connection(Connection("P", "omega", "Counter", "signal"))
    system.add_event_connection(EventConnection("P", "wall_hit", "Counter", "tick"))
    system.set_algorithm(HybridAlgorithm(tol_time=1e-10))
    system.initialize(0.0)
    result = system.run(0.0, 1.5, 0.25)
    hits = [e for e in result.events if e.event == "wall_hit"]
    ticks = [e for e in result.events if e.event == "tick"]
    assert len(hits) == 2 and [e.t for e in ticks] == [e.t for e in hits]
    assert hits[0].t == pytest.approx(WALL_HIT, abs=1e-9)
    counter = system.components["Counter"]
    assert counter.outputs["count"].value == 2
    assert counter.outputs["last_tick"].raw() == hits[-1].t
    t, values = result["Counter"]
    at_hit = np.flatnonzero(t == hits[0].t)
    # the tick sampled the angular velocity at the hit, before the bounce reversed it
    assert values["sampled"][at_hit[-1]] < 0


class Listener(CoSimComponent):
    """Writes down the events it hears and when."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.heard: list[tuple[list[str], float]] = []
        self.add_event_handler("on_full", lambda c, names, t: self.heard.append((names, t)))

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        pass


def test_an_output_clock_reaches_a_python_handler_and_a_declarative_one() -> None:
    system = tank_and_counter(connect=False)
    listener = Listener("L")
    system.add_component(listener)
    other = FMUComponent("Other", fmus.path(TANK))
    other.set_parameters(threshold=10.0)
    other.add_event_handler("refill", Reinitialize(level0=0.05))
    system.add_component(other)
    system.add_event_connection(EventConnection("Tank", "full", "L", "on_full"))
    system.add_event_connection(EventConnection("Tank", "full", "Other", "refill"))
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.25)
    assert [names for names, _ in listener.heard] == [["full"]] * 3
    assert [t for _, t in listener.heard] == pytest.approx(FULL_TIMES, abs=1e-12)
    # Other restarts with level0 = 0.05 at the communication point after each tick
    values = result["Other"][1]
    assert list(values["level"]) == pytest.approx([0, 0.25, 0.05, 0.05, 0.05])


def ticks_and_a_wall_hit(threads: int = 1, dt: float = 0.25,
                         threshold: float = 0.4) -> list[tuple[float, int, str, str]]:
    """A tank full at 0.4 (threshold 0.4) and a wall hit at 0.465, both in the step from 0.25
    to 0.5; the hit ticks a counter, the tank's clock another (at the tank's tick)."""
    system = System("ticks and a hit")
    add_bouncing_pendulum(system)
    tank = FMUComponent("Tank", fmus.path(TANK))
    tank.set_parameters(threshold=threshold)
    for component in (tank, FMUComponent("Hits", fmus.path(COUNTER)),
                      FMUComponent("Fills", fmus.path(COUNTER))):
        system.add_component(component)
    system.add_connection(Connection("P", "theta", "Hits", "signal"))
    system.add_connection(Connection("Tank", "level", "Fills", "signal"))
    system.add_event_connection(EventConnection("P", "wall_hit", "Hits", "tick"))
    system.add_clock_connection("Tank.full", "Fills.tick")
    system.set_algorithm(HybridAlgorithm(tol_time=1e-10,
                                         coupling=GaussSeidelAlgorithm(threads=threads)))
    system.initialize(0.0)
    events = system.run(0.0, 1.0, dt).events
    return [(e.t, e.micro, e.component, e.event) for e in events]


def test_a_tick_after_a_hit_in_one_step_keeps_the_hit_s_tick() -> None:
    """The hit's tick at 0.465 is recorded when the master goes on from the hit; the tank's
    tick at 0.48 after it, in the same step, steps the system back to the hit: the hit's tick
    stays recorded once."""
    names = [(r[2], r[3]) for r in ticks_and_a_wall_hit(threshold=0.48) if r[0] < 0.5]
    assert names == [("P", "wall_hit"), ("Hits", "tick"), ("Tank", "fmu_event"),
                     ("Tank", "full"), ("Fills", "tick")]


@pytest.mark.parametrize("dt", [0.1, 0.25])
def test_located_ticks_leave_the_seed_pendulum_s_wall_hit_where_it_was(dt: float) -> None:
    records = ticks_and_a_wall_hit(dt=dt)
    hits = [r[0] for r in records if r[3] == "wall_hit"]
    fills = [r[0] for r in records if r[2] == "Fills"]
    assert hits[0] == pytest.approx(WALL_HIT, abs=1e-9)
    # the tank is full at 0.4 and 0.8; the algorithm's tol_time is 1e-10
    assert fills == pytest.approx([0.4, 0.8], abs=1e-10)


def test_a_tick_and_an_indicator_in_one_step_are_recorded_in_superdense_order() -> None:
    records = ticks_and_a_wall_hit()
    names = [(r[2], r[3]) for r in records if r[0] < 0.5]
    assert names == [("Tank", "fmu_event"), ("Tank", "full"), ("Fills", "tick"),
                     ("P", "wall_hit"), ("Hits", "tick")]
    assert records[1][0] == pytest.approx(0.4, abs=1e-12)
    assert records[3][0] == pytest.approx(WALL_HIT, abs=1e-9)
    # the tank's tick reaches its counter at its own instant, before the hit; the hit's tick
    # comes after the hit, at the same instant
    assert records[0][:2] == records[1][:2] == records[2][:2] == (records[1][0], 0)
    assert records[3][:2] == records[4][:2] == (records[3][0], 0)
    assert records == sorted(records, key=lambda r: (r[0], r[1]))
    # the same records in every run and on two threads
    assert ticks_and_a_wall_hit() == records
    assert ticks_and_a_wall_hit() == records
    assert ticks_and_a_wall_hit(threads=2) == records


def test_a_clock_connection_is_refused_naming_what_is_wrong() -> None:
    system = tank_and_counter(connect=False)
    with pytest.raises(ConfigurationError, match=r"'Counter' has no triggered input clock "
                                                 r"'count'; triggered input clocks: \['tick'\]"):
        system.add_clock_connection("Tank.full", "Counter.count")
    with pytest.raises(ConfigurationError, match=r"'Tank' has no event indicator 'level'; "
                                                 r"indicators: none, output clocks: \['full'\]"):
        system.add_clock_connection("Tank.level", "Counter.tick")
    with pytest.raises(ConfigurationError, match="not on all of a component's own events"):
        system.add_event_connection(EventConnection.own_events("Tank", "Counter", "tick"))


def test_clock_connections_from_yaml(tmp_path: Path) -> None:
    path = tmp_path / "clocks.yaml"
    path.write_text(textwrap.dedent(f"""\
        system: {{name: clocks}}
        components:
          - {{name: Tank, fmu: {TANK}}}
          - {{name: Counter, fmu: {COUNTER}}}
        connections: [{{src: Tank.level, dst: Counter.signal}}]
        clock_connections: [{{src: Tank.full, dst: Counter.tick}}]
        run: {{t0: 0.0, tf: 1.0, dt: 0.25}}
        """))
    system = build_system(path)
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.25)
    assert list(result["Counter"][1]["count"]) == [0, 0, 1, 2, 3]


def test_clock_connections_from_ssp(tmp_path: Path) -> None:
    """SSP 1.0 has no connector type for a clock: a connection between two untyped connectors
    that name an output clock and a triggered input clock is a clock connection."""
    system = textwrap.dedent(f"""\
        <ssd:System name="root">
          <ssd:Elements>
            <ssd:Component name="Tank" source="resources/{TANK}.fmu">
              <ssd:Connectors>
                <ssd:Connector name="level" kind="output"><ssc:Real/></ssd:Connector>
                <ssd:Connector name="full" kind="output"/>
              </ssd:Connectors>
            </ssd:Component>
            <ssd:Component name="Counter" source="resources/{COUNTER}.fmu">
              <ssd:Connectors>
                <ssd:Connector name="signal" kind="input"><ssc:Real/></ssd:Connector>
                <ssd:Connector name="tick" kind="input"/>
              </ssd:Connectors>
            </ssd:Component>
          </ssd:Elements>
          <ssd:Connections>
            <ssd:Connection startElement="Tank" startConnector="level" endElement="Counter"
                            endConnector="signal"/>
            <ssd:Connection startElement="Tank" startConnector="full" endElement="Counter"
                            endConnector="tick"/>
          </ssd:Connections>
        </ssd:System>""")
    system = load_ssp(write_ssp(tmp_path / "clocks.ssp", ssd(system), bundled=(TANK, COUNTER)))
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.25)
    assert list(result["Counter"][1]["count"]) == [0, 0, 1, 2, 3]
