"""FMI 3.0 countdown and changing clocks in Co-Simulation, with the toolchain's timer_fmi3: it
announces its first alarm `delay` seconds ahead (fmi3GetIntervalDecimal, qualifier changed)
and, at each alarm, the next one `growth` times further ahead than the last. With delay 0.1 and
growth 2 the alarms ring at 0.1, 0.3, 0.7 and 1.5 s: the engine asks for the interval after
initialization and after every Event Mode, and ends the FMU's step at each planned alarm.
metronome_fmi3's changing clock beats every announced interval: 0.2 s, halved after 3 beats,
so at 0.2, 0.4, 0.6, 0.7, 0.8, ..."""

from __future__ import annotations

import pytest
from bouncing_pendulum import add_bouncing_pendulum
from fmpy.validation import validate_fmu
from syssimx import (
    FMUComponent,
    GaussSeidelAlgorithm,
    HybridAlgorithm,
    System,
    fmus,
)
from syssimx.engine import ffi, lib

TIMER = "timer_fmi3"
ALARMS = (0.1, 0.3, 0.7, 1.5)


def timer_system(pendulum: bool = False, threads: int = 1) -> System:
    system = System("timer")
    system.add_component(FMUComponent("T", fmus.path(TIMER)))
    if pendulum:
        add_bouncing_pendulum(system)
        system.set_algorithm(HybridAlgorithm(tol_time=1e-10,
                                             coupling=GaussSeidelAlgorithm(threads=threads)))
    return system


def test_fmpy_validates_the_timer() -> None:
    assert validate_fmu(fmus.path(TIMER)) == []


@pytest.mark.parametrize("dt", [0.1, 0.25, 1.0])
def test_the_alarms_ring_at_the_announced_intervals_whatever_the_step(dt: float) -> None:
    system = timer_system()
    system.initialize(0.0)
    result = system.run(0.0, 2.0, dt)
    assert [e.t for e in result.events] == pytest.approx(ALARMS, abs=1e-12)
    assert all(e.event == "clock_tick" and e.own for e in result.events)
    t, values = result["T"]
    assert list(values["count"]) == [sum(a <= time + 1e-12 for a in ALARMS) for time in t]


@pytest.mark.parametrize("offset", [-1e-6, 0.0, 1e-6])
def test_count_just_before_at_and_just_after_each_alarm(offset: float) -> None:
    system = timer_system()
    system.initialize(0.0)
    start = 0.0
    for k, alarm in enumerate(ALARMS):
        system.run(start, alarm + offset, alarm + offset - start)
        start = alarm + offset
        timer = system.components["T"]
        assert timer.outputs["count"].raw() == (k if offset < 0 else k + 1)
        assert timer.outputs["last_alarm"].raw() == pytest.approx(
            ALARMS[k - 1] if offset < 0 and k > 0 else -1 if offset < 0 else alarm, abs=1e-12)


def alarms_and_hits(threads: int = 1) -> list[tuple[float, int, str, str]]:
    system = timer_system(pendulum=True, threads=threads)
    system.initialize(0.0)
    events = system.run(0.0, 2.0, 0.25).events
    return [(e.t, e.micro, e.component, e.event) for e in events]


def test_a_rolled_back_step_keeps_the_alarms_planned() -> None:
    """Locating the wall hits restores the timer to earlier states, before alarms it had
    planned and rung: each restore brings back the plan of its state, so the alarms ring as
    without the pendulum, once each, the same in every run and on two threads."""
    records = alarms_and_hits()
    alarms = [r[0] for r in records if r[3] == "clock_tick"]
    hits = [r[0] for r in records if r[3] == "wall_hit"]
    assert alarms == pytest.approx(ALARMS, abs=1e-12)
    assert len(hits) == 2 and 0.25 < hits[0] < 0.5  # located by rollback beside an alarm
    assert records == sorted(records, key=lambda r: (r[0], r[1]))
    assert alarms_and_hits() == records
    assert alarms_and_hits(threads=2) == records


def test_the_plan_carries_the_countdown_clock() -> None:
    """The timer's countdown clock is a record of its type table, which the engine reads back."""
    text = timer_system().to_plan()
    vr = FMUComponent("T", fmus.path(TIMER)).info.clocks.by_name("alarm").value_reference
    assert f"fmi3_countdown_clock 0 {vr}\n" in text
    error = ffi.new("char[]", 2048)
    plan = lib().ssx_plan_read(text.encode(), len(text.encode()), error, 2048)
    assert plan != ffi.NULL, ffi.string(error).decode()
    lib().ssx_plan_free(plan)


BEATS = (0.2, 0.4, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2)


@pytest.mark.parametrize("dt", [0.1, 0.3, 1.2])
def test_a_changing_clock_beats_every_announced_interval(dt: float) -> None:
    system = System("metronome")
    system.add_component(FMUComponent("M", fmus.path("metronome_fmi3")))
    system.initialize(0.0)
    result = system.run(0.0, 1.2, dt)
    assert [e.t for e in result.events] == pytest.approx(BEATS, abs=1e-9)
    assert system.components["M"].outputs["count"].raw() == len(BEATS)
    text = system.to_plan()
    vr = FMUComponent("M", fmus.path("metronome_fmi3")).info.clocks.by_name("beat").value_reference
    assert f"fmi3_changing_clock 0 {vr}\n" in text
