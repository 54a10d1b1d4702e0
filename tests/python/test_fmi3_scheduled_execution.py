"""FMI 3.0 Scheduled Execution: the Reference FMUs' Clocks.fmu run as a component of a System
(ScheduledExecutionComponent), tick by tick against the table in its modelDescription's
comment, and the order of ticks at one instant; our own Scheduled Execution FMU
(tests/fmus/fmi3_scheduled, built by meson) for a clock whose interval only the FMU gives and
changes, and for an FMU that unbalances its preemption lock or fails in a partition.

FMPy 0.3.32 does not run Scheduled Execution FMUs (its simulate_fmu accepts only
fmi_type="ModelExchange" or "CoSimulation" and refuses Clocks.fmu), so the expected ticks are
the description's table and the FMU's documented rule for outClock: it ticks after the
partition that makes the total of input clock ticks a multiple of 5.
"""

from __future__ import annotations

import gc
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from reference_root import reference_root
from syssimx import (
    EventConnection,
    GaussSeidelAlgorithm,
    HybridAlgorithm,
    ScheduledExecutionComponent,
    System,
)
from syssimx._paths import build_dir
from syssimx.bridge.history_arrays import HistoryArrays
from syssimx.components.base import CoSimComponent
from syssimx.components.scheduled_execution import Tick
from syssimx.engine import ffi, lib
from syssimx.errors import ConfigurationError, FMUFileError, SimulationError
from test_fmi3_import import edited

FOLDER = reference_root() / "fmi3"
reference = pytest.mark.skipif(not FOLDER.is_dir(), reason=(
    f"the FMI 3.0 Reference FMUs are absent (no folder {FOLDER}): set SYSSIMX_REFERENCE_FMUS "
    "to the folder holding fmi3/"))
ROOT = Path(__file__).resolve().parents[2]
CLOCKS = str(FOLDER / "Clocks.fmu")

# the table in Clocks.fmu's modelDescription: which input clock ticks when over 10 s
TABLE = {"inClock1": [0, 1, 2, 3, 4, 5, 6, 7, 8, 9], "inClock2": [0, 1, 8, 9],
         "inClock3": [4]}


def _component(path: str = CLOCKS) -> ScheduledExecutionComponent:
    component = ScheduledExecutionComponent("C", path)
    component.schedule_clock("inClock2", times=[0, 1, 8, 9])
    return component


def _run(component: ScheduledExecutionComponent, dt: float) -> dict:
    system = System("clocks")
    system.add_component(component)
    system.initialize(0.0)
    return system.run(0.0, 10.0, dt)


def _expected_ticks() -> list[tuple[float, str]]:
    """The table's ticks in the order syssimx activates them (by time, then priority: inClock1
    0, inClock2 1, inClock3 2), each followed by outClock when it brings the total of input
    ticks to a multiple of 5."""
    order = {"inClock1": 0, "inClock2": 1, "inClock3": 2}
    ticks = sorted(((t, clock) for clock, times in TABLE.items() for t in times),
                   key=lambda tick: (tick[0], order[tick[1]]))
    expected = []
    for total, tick in enumerate(ticks, start=1):
        expected.append(tick)
        if total % 5 == 0:
            expected.append((tick[0], "outClock"))
    return expected


@reference
def test_clocks_fmu_ticks_as_its_description_tabulates():
    component = _component()
    result = _run(component, 1.0)
    assert [(tick.time, tick.clock) for tick in component.ticks] == _expected_ticks()
    outclock = [tick.time for tick in component.ticks if tick.clock == "outClock"]
    assert outclock == [2.0, 6.0, 9.0]
    # each partition's counters, read right after it
    for clock, times in TABLE.items():
        counts = [tick.values[f"{clock}Ticks"] for tick in component.ticks
                  if tick.clock == clock]
        assert counts == list(range(1, len(times) + 1))
    totals = [tick.values["totalInClockTicks"] for tick in component.ticks
              if tick.clock != "outClock"]
    assert totals == list(range(1, 16))
    assert component.ticks[8] == Tick(4.0, "inClock3", {"inClock3Ticks": 1,
                                                         "totalInClockTicks": 8,
                                                         "output3": 1000})
    # the ports at t hold what the ticks before t left: the step from t activates [t, t + dt)
    t, values = result["C"]
    assert t.tolist() == [float(i) for i in range(11)]
    assert values["inClock1Ticks"].tolist() == list(range(11))
    assert values["inClock2Ticks"].tolist() == [0, 1, 2, 2, 2, 2, 2, 2, 2, 3, 4]
    assert values["inClock3Ticks"].tolist() == [0] * 5 + [1] * 6
    assert values["totalInClockTicks"].tolist() == [0, 2, 4, 5, 6, 8, 9, 10, 11, 13, 15]


@reference
@pytest.mark.parametrize("dt", [10.0, 0.25, 2.5])
def test_the_ticks_do_not_depend_on_the_step(dt: float):
    component = _component()
    _run(component, dt)
    assert [(tick.time, tick.clock) for tick in component.ticks] == _expected_ticks()


@reference
def test_ticks_at_one_instant_run_in_priority_order(tmp_path: Path):
    swapped = edited(tmp_path, CLOCKS,
                     ('intervalDecimal="1.0" priority="0"', 'intervalDecimal="1.0" priority="1"'),
                     ('intervalVariability="triggered" priority="1"',
                      'intervalVariability="triggered" priority="0"'))
    component = _component(swapped)
    _run(component, 1.0)
    at_zero = [tick.clock for tick in component.ticks if tick.time == 0.0]
    assert at_zero == ["inClock2", "inClock1"]
    as_given = _component()
    _run(as_given, 1.0)
    assert [tick.clock for tick in as_given.ticks if tick.time == 0.0] == ["inClock1",
                                                                          "inClock2"]


@reference
def test_the_inputs_are_set_before_each_partition():
    component = _component()
    component.set_inputs({"input2": 3})
    _run(component, 10.0)  # one step: input2 is set again before each inClock2 tick
    assert [tick.values["result2"] for tick in component.ticks
            if tick.clock == "inClock2"] == [3, 6, 9, 12]


@reference
def test_a_component_on_its_own_runs_its_ticks():
    component = _component()
    component.initialize(0.0)
    component.do_step(0.0, 10.0)
    assert [(tick.time, tick.clock) for tick in component.ticks] == _expected_ticks()
    assert component.get_outputs()["totalInClockTicks"] == 15
    component.free()


@reference
def test_schedule_clock_takes_only_a_triggered_input_clock():
    component = ScheduledExecutionComponent("C", CLOCKS)
    with pytest.raises(ConfigurationError) as info:
        component.schedule_clock("inClock1", times=[0.5])
    assert str(info.value) == (
        "component 'C': clock 'inClock1' is input with intervalVariability constant; "
        "schedule_clock takes the times of a triggered input clock (the others tick by "
        "their interval or by the FMU)")
    with pytest.raises(ConfigurationError) as info:
        component.schedule_clock("inClock9", times=[0.5])
    assert str(info.value) == ("component 'C': no clock 'inClock9' (clocks: inClock1, "
                               "inClock2, inClock3, outClock)")


@reference
def test_an_fmu_without_scheduled_execution_is_refused():
    path = FOLDER / "Feedthrough.fmu"
    with pytest.raises(FMUFileError) as info:
        ScheduledExecutionComponent("F", path)
    assert str(info.value) == (f"{path}: the FMU declares no ScheduledExecution "
                               "(FMUComponent runs Co-Simulation and Model Exchange FMUs)")


@reference
def test_a_dropped_component_frees_its_instance():
    import gc
    import weakref

    component = _component()
    _run(component, 10.0)
    gone = weakref.ref(component)
    del component
    gc.collect()
    assert gone() is None


def _own(stem: str) -> str:
    build = build_dir() or ROOT / "build" / "release"
    path = build / "tests" / "fmus" / "fmi3_scheduled" / f"{stem}.fmu"
    if not path.is_file():
        pytest.skip(f"the Scheduled Execution test FMU is not built ({path} is missing): run "
                    "meson compile")
    return str(path)


def test_a_tunable_clock_ticks_at_the_fmus_intervals_and_countdown_and_output_clocks_follow():
    component = ScheduledExecutionComponent("S", _own("fmi3_scheduled"))
    component.set_inputs({"gain": 2.0})
    result = _run_for(component, 4.0, 1.0)
    # tick: 0.5 s, then 1 s from its second tick; later: 0.25 s after each odd tick; alarm:
    # with every third tick
    assert [(tick.time, tick.clock) for tick in component.ticks] == [
        (0.0, "tick"), (0.25, "later"), (0.5, "tick"), (1.5, "tick"), (1.5, "alarm"),
        (1.75, "later"), (2.5, "tick"), (3.5, "tick"), (3.75, "later")]
    assert [tick.values for tick in component.ticks if tick.clock == "tick"] == [
        {"count": n, "sum": 2.0 * n} for n in range(1, 6)]
    assert [tick.values for tick in component.ticks if tick.clock == "later"] == [
        {"laterCount": n} for n in range(1, 4)]
    _, values = result["S"]
    assert values["count"].tolist() == [0, 2, 3, 4, 5]


def _run_for(component: ScheduledExecutionComponent, stop: float, dt: float) -> dict:
    system = System("scheduled")
    system.add_component(component)
    system.initialize(0.0)
    return system.run(0.0, stop, dt)


def test_a_partition_that_unlocks_preemption_it_never_locked_is_an_error():
    component = ScheduledExecutionComponent("S", _own("fmi3_scheduled_unbalanced"))
    with pytest.raises(SimulationError, match=r"S: the FMU unlocked preemption it had not "
                                              r"locked.* at t=0"):
        _run_for(component, 1.0, 1.0)


def test_a_failing_partition_names_the_function_and_time():
    component = ScheduledExecutionComponent("S", _own("fmi3_scheduled_failing"))
    with pytest.raises(SimulationError, match=r"S: fmi3ActivateModelPartition returned "
                                              r"fmi3Error.* at t=1"):
        _run_for(component, 4.0, 1.0)
    assert [tick.time for tick in component.ticks if tick.clock == "tick"] == [0.0, 0.5]


@reference
def test_a_yaml_system_gives_the_triggered_clock_times(tmp_path: Path):
    from syssimx.system.loader import build_system

    description = tmp_path / "clocks.yaml"
    description.write_text(
        "system: {name: clocks}\n"
        "components:\n"
        "  - name: C\n"
        "    class: syssimx:ScheduledExecutionComponent\n"
        f"    args: {{fmu_path: {CLOCKS}, clock_times: {{inClock2: [0, 1, 8, 9]}}}}\n")
    system = build_system(description)
    system.initialize(0.0)
    system.run(0.0, 10.0, 1.0)
    component = system.components["C"]
    assert [(tick.time, tick.clock) for tick in component.ticks] == _expected_ticks()


def _plan_run(text: str, stop: float, dt: float) -> tuple[list[tuple[float, int]], Any]:
    """The ticks (time, clock index) and the history of component 0 of the engine's own build
    of `text`: no FMU given, no Python anywhere, ssx_plan_initialize at 0, one ssx_run."""
    engine = lib()
    data = text.encode()
    error = ffi.new("char[2048]")
    plan = ffi.gc(engine.ssx_plan_read(data, len(data), error, 2048), engine.ssx_plan_free)
    assert plan != ffi.NULL, ffi.string(error).decode()
    system = engine.ssx_plan_build(plan, b"", ffi.NULL, 0, error, 2048)
    assert system != ffi.NULL, ffi.string(error).decode()
    system = ffi.gc(system, engine.ssx_system_free)
    assert engine.ssx_plan_initialize(system, plan, 0.0) == 0
    assert engine.ssx_run(system, 0.0, stop, dt) == 0
    count = ffi.new("size_t *")
    n = engine.ssx_scheduled_tick_count(system, 0, count)
    times, clocks = ffi.new("double[]", n), ffi.new("int[]", n)
    first = ffi.new("size_t[]", n + 1)
    outputs, values = ffi.new("int[]", count[0]), ffi.new("double[]", count[0])
    assert engine.ssx_scheduled_ticks(system, 0, times, clocks, first, outputs, values) == 0
    history = HistoryArrays(system, engine.ssx_history_release)
    outputs = engine.ssx_plan_port_count(plan, 0, 0)
    return [(times[k], clocks[k]) for k in range(n)], history.values(0, outputs).copy()


@reference
def test_the_engine_alone_runs_the_components_plan_with_the_same_ticks():
    component = _component()
    system = System("clocks")
    system.add_component(component)
    system.initialize(0.0)
    text = system.to_plan()
    assert "\nscheduled_clock 0 1 1002 1 nan 0 0 4 0 1 8 9\n" in text  # inClock2
    ticks, history = _plan_run(text, 10.0, 1.0)
    names = ["inClock1", "inClock2", "inClock3", "outClock"]  # inputs, then outputs
    assert [(t, names[clock]) for t, clock in ticks] == _expected_ticks()
    system.run(0.0, 10.0, 1.0)
    _, values = system.get_history()["C"]
    for k, port in enumerate(component.engine_outputs()):
        np.testing.assert_array_equal(history[:, k], values[port])


@reference
def test_no_python_runs_per_tick():
    """A profile hook counts the Python calls of a one-step run: ten times the ticks, the same
    calls."""
    def python_calls(stop: float) -> tuple[int, int]:
        component = _component()
        system = System("clocks")
        system.add_component(component)
        system.initialize(0.0)
        system.run(0.0, stop, stop)  # the first run imports and caches what runs need
        system.initialize(0.0)
        calls = 0

        def count(_frame: Any, event: str, _arg: Any) -> None:
            nonlocal calls
            calls += event == "call"

        gc.disable()  # no finalizer may run Python inside the measured run
        sys.setprofile(count)
        try:
            system.run(0.0, stop, stop)
        finally:
            sys.setprofile(None)
            gc.enable()
        return calls, len(component.ticks)

    few, many = python_calls(10.0), python_calls(100.0)
    assert few[1] == len(_expected_ticks()) and many[1] > 5 * few[1]
    assert many[0] == few[0]


@reference
@pytest.mark.parametrize("threads", [1, 2])
def test_two_components_on_threads_tick_as_on_one(threads: int):
    system = System("clocks")
    components = [_component(), _component()]
    for name, component in zip("AB", components, strict=True):
        component.name = name
        system.add_component(component)
    system.set_algorithm(HybridAlgorithm(coupling=GaussSeidelAlgorithm(threads=threads)))
    system.initialize(0.0)
    events = system.run(0.0, 10.0, 1.0).events
    for component in components:
        assert [(tick.time, tick.clock) for tick in component.ticks] == _expected_ticks()
    # outClock is an own event of each component, A's before B's at one instant
    assert [(e.t, e.component, e.event) for e in events] == [
        (t, name, "outClock") for t in (2.0, 6.0, 9.0) for name in "AB"]


class _Listener(CoSimComponent):
    """Writes down when it hears outClock."""

    def __init__(self) -> None:
        super().__init__("L")
        self.heard: list[float] = []
        self.add_event_handler("on_out", lambda _c, _names, t: self.heard.append(t))

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        pass


@reference
def test_an_output_clock_reaches_an_event_connection():
    system = System("clocks")
    system.add_component(_component())
    listener = _Listener()
    system.add_component(listener)
    system.add_event_connection(EventConnection("C", "outClock", "L", "on_out"))
    system.initialize(0.0)
    system.run(0.0, 10.0, 1.0)
    assert listener.heard == [2.0, 6.0, 9.0]
