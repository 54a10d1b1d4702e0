"""A System written as a plan (System.to_plan, write_plan) is what the engine builds from: the
engine alone, reading the text, builds, initializes and runs the Python-built run bit for bit,
and refuses what only Python can attach, naming the component."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pendulum_wall
import pytest
from syssimx import Connection, EventConnection, FMUComponent, Reinitialize, System, fmus
from syssimx.bridge.history_arrays import HistoryArrays
from syssimx.engine import ffi, lib
from syssimx.errors import ConfigurationError
from syssimx.fmu.archive import extract
from syssimx.plan.records import Doubles, PlanRecords, Word

_ERROR_SIZE = 2048
STOP, STEP = 3.0, 0.05


class EngineRefusalError(Exception):
    """What the engine said when it refused to build or initialize a plan."""


def _read(text: str) -> Any:
    data = text.encode()
    error = ffi.new("char[]", _ERROR_SIZE)
    plan = lib().ssx_plan_read(data, len(data), error, _ERROR_SIZE)
    assert plan != ffi.NULL, ffi.string(error).decode()
    return ffi.gc(plan, lib().ssx_plan_free)


def _run_standalone(text: str, base_folder: Path | None = None, component: int = 0
                    ) -> tuple[np.ndarray, np.ndarray, list[float]]:
    """(time, outputs of `component`, event times) of the engine's own build of `text`: no
    FMU given, ssx_plan_initialize at 0, one ssx_run."""
    engine = lib()
    plan = _read(text)
    error = ffi.new("char[]", _ERROR_SIZE)
    folder = str(base_folder).encode() if base_folder is not None else b""
    system = engine.ssx_plan_build(plan, folder, ffi.NULL, 0, error, _ERROR_SIZE)
    if system == ffi.NULL:
        raise EngineRefusalError(ffi.string(error).decode())
    system = ffi.gc(system, engine.ssx_system_free)
    if engine.ssx_plan_initialize(system, plan, 0.0) < 0 or \
            engine.ssx_run(system, 0.0, STOP, STEP) < 0:
        raise EngineRefusalError(ffi.string(engine.ssx_last_error(system).message).decode())
    history = HistoryArrays(system, engine.ssx_history_release)
    record = ffi.new("ssx_event_record *")
    events = []
    for k in range(engine.ssx_event_count(system)):
        assert engine.ssx_event_get(system, k, record) == 0
        events.append(float(record.t))
    outputs = engine.ssx_plan_port_count(plan, component, 0)
    return history.time().copy(), history.values(component, outputs).copy(), events


def _python_run(system: System, name: str = "P") -> tuple[np.ndarray, np.ndarray, list[float]]:
    result = system.run(0.0, STOP, STEP)
    time, columns = system.get_history()[name]
    outputs = system.components[name].engine_outputs()  # the engine's columns, in its order
    return np.asarray(time), np.column_stack([columns[name] for name in outputs]), \
        [event.t for event in result.events]


def _wall(solver: str = "cvode") -> System:
    system, _ = pendulum_wall.build(solver, handler=Reinitialize(theta0="theta",
                                                                 omega0="-omega"))
    return system


@pytest.mark.parametrize("solver", ["cvode", "euler"])
def test_the_engine_alone_runs_the_pendulum_against_a_wall_bit_for_bit(solver: str) -> None:
    system = _wall(solver)
    text = system.to_plan()
    time, values, events = _run_standalone(text)
    python_time, python_values, python_events = _python_run(system)
    assert len(events) == 3
    assert events == python_events
    np.testing.assert_array_equal(time, python_time)
    np.testing.assert_array_equal(values, python_values)
    if solver == "cvode":
        assert abs(events[0] - pendulum_wall.QUARTER_PERIOD) < 1e-9


def test_the_engines_writer_gives_pythons_text_back() -> None:
    text = _wall().to_plan()
    size = ffi.new("size_t *")
    written = lib().ssx_plan_write(_read(text), size)
    try:
        assert ffi.string(written, size[0]).decode() == text
    finally:
        lib().ssx_plan_text_free(written)


def test_a_written_plan_finds_its_fmu_in_the_folder_given(tmp_path: Path) -> None:
    system = _wall()
    extract(Path(fmus.path("pendulum_cvode")), tmp_path / "members" / "P")
    path = system.write_plan(tmp_path / "wall.plan", folders={"P": "members/P"})
    text = path.read_text()
    assert '"members/P"' in text
    time, values, events = _run_standalone(text, tmp_path)
    python_time, python_values, python_events = _python_run(system)
    assert events == python_events
    np.testing.assert_array_equal(values, python_values)
    np.testing.assert_array_equal(time, python_time)
    with pytest.raises(ConfigurationError, match="'Q' is no FMU component"):
        system.to_plan(folders={"Q": "members/Q"})


def test_a_python_event_handler_is_refused_by_a_build_without_python() -> None:
    system, _ = pendulum_wall.build("euler")  # its handler: the Python function `bounce`
    with pytest.raises(EngineRefusalError,
                       match=r"component 'P' runs Python \(its 'hooks' record\)"):
        _run_standalone(system.to_plan())


def test_a_python_component_is_refused_by_a_build_without_python() -> None:
    from quickstart import Integrator

    source = FMUComponent("P", fmus.path("pendulum_euler"))
    system = System("driven")
    system.add_component(source)
    system.add_component(Integrator(name="Integrator", x0=0.0))
    system.add_connection(Connection("P", "theta", "Integrator", "u"))
    text = system.to_plan()
    assert 'python "Integrator" ' in text
    with pytest.raises(EngineRefusalError,
                       match=r"component 'Integrator' runs Python \(its 'python' record\)"):
        _run_standalone(text)
    system.initialize(0.0)  # the plan written is the one Python builds on
    system.run(0.0, 0.2, 0.1)
    assert system.get_history()["Integrator"][0][-1] == 0.2


def test_a_python_indicator_function_is_a_placeholder_record() -> None:
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.add_event_indicator("low", func=lambda c: c.outputs["theta"].get().magnitude)
    pendulum.add_event_handler("omega_invert", Reinitialize(omega0="-omega"))
    system = System("wall")
    system.add_component(pendulum)
    system.add_event_connection(EventConnection("P", "low", "P", "omega_invert"))
    assert "\nindicator_callback 0 0\n" in system.to_plan()
    with pytest.raises(EngineRefusalError, match=r"its 'indicator_callback' record"):
        _run_standalone(system.to_plan())


def test_records_write_each_field_as_the_format_reads_it() -> None:
    records = PlanRecords()
    records.add("x", True, 3, 0.05, 1e-10, float("nan"), float("-inf"), Word("real"),
                'a "q"\n\t\x01\u00e9', b"\x00\xff", [(1, 2.5), (3, 0.1)])
    assert records.text().splitlines()[1] == (
        'x 1 3 0.05 1e-10 nan -inf real "a \\"q\\"\\n\\t\\x01\u00e9" "\\x00\\xff" '
        "2 1 2.5 3 0.1")
    column = np.array([0.1, 1 / 3, 5e-324, np.nan, -np.inf, 100.0, 1e22])
    records.add("y", Doubles(column))
    line = records.text().splitlines()[2]
    assert line == "y 7 0.1 0.3333333333333333 4.94065645841247e-324 nan -inf 100 1e+22"
    np.testing.assert_array_equal(np.array(line.split()[2:], dtype=float), column)


def test_a_long_list_of_doubles_is_written_in_hex_exactly() -> None:
    """More than 64 doubles: `xN:` and each value's little-endian binary64 bytes in one
    token, to the bit (a NaN's payload, -0); 64 stay decimal."""
    column = np.arange(65, dtype=np.float64) / 3
    column[1:3] = np.array([0x7FF8000000000ABC], dtype=np.uint64).view(np.float64)[0], -0.0
    records = PlanRecords()
    records.add("y", Doubles(column))
    records.add("y", Doubles(column[:64]))
    long_line, short_line = records.text().splitlines()[1:]
    count, digits = long_line.removeprefix("y x").split(":")
    assert count == "65" and digits == digits.lower() and len(digits) == 65 * 16
    decoded = np.frombuffer(bytes.fromhex(digits), dtype="<f8")
    assert decoded.tobytes() == column.tobytes()
    assert short_line.startswith("y 64 0 nan -0 1 1.3333333333333333 ")


def _large_table_system(rows: int = 200_000) -> System:
    """A table of `rows` rows and 3 columns (a DataFrame) into a gain, initialized."""
    import pandas as pd
    from syssimx.components.table_source import TableSource

    rng = np.random.default_rng(7)
    time = np.linspace(0.0, 10.0, rows)
    frame = pd.DataFrame({"time": time, "u": rng.standard_normal(rows), "b": np.sin(time) / 3,
                          "c": rng.uniform(0.0, 1e6, rows)})
    system = System("large table")
    system.add_component(TableSource("T", frame))
    system.add_component(FMUComponent("G", fmus.path("gain")))
    system.add_connection(Connection("T", "u", "G", "u", convert_units=False))
    system.initialize(0.0)
    return system


def test_a_large_table_runs_bit_identically_in_its_hex_form(monkeypatch: Any) -> None:
    """The plan of a 200,000-row table holds its lists in hex; the engine's writer gives the
    text back byte for byte (as it does for a 64-row table's decimal lists), the engine alone
    runs it as Python does, and the run is the run of the same plan in decimal, to the bit."""
    from syssimx.plan import records

    system = _large_table_system()
    text = system.to_plan()
    assert '\ntable "T" x200000:' in text and "\ntable_column 0 real 0 x200000:" in text
    short = _large_table_system(rows=64).to_plan()
    assert '\ntable "T" 64 0 0.15873015873015872 ' in short
    for plan in (text, short):
        size = ffi.new("size_t *")
        written = lib().ssx_plan_write(_read(plan), size)
        try:
            assert ffi.string(written, size[0]).decode() == plan
        finally:
            lib().ssx_plan_text_free(written)
    time, values, _ = _run_standalone(text)
    python_time, python_values, _ = _python_run(system, "T")
    np.testing.assert_array_equal(time, python_time)
    np.testing.assert_array_equal(values, python_values)
    gain = system.get_history()["G"][1]

    monkeypatch.setattr(records, "DECIMAL_DOUBLES_MAX", 10**9)
    decimal = _large_table_system()
    assert '\ntable "T" 200000 0 ' in decimal.to_plan()
    decimal_time, decimal_values, _ = _python_run(decimal, "T")
    np.testing.assert_array_equal(decimal_time, python_time)
    np.testing.assert_array_equal(decimal_values, python_values)
    for name, column in decimal.get_history()["G"][1].items():
        np.testing.assert_array_equal(column, gain[name])


def test_an_fmi3_fmu_is_built_from_the_type_table_python_loaded_it_with() -> None:
    ball = FMUComponent("P", fmus.path("bouncing_ball_cvode_fmi3"))
    ball.set_parameters(h0=1.0, v0=0.0)
    ball.add_event_indicator("floor", variable="h", direction=-1)
    ball.add_event_handler("bounce", Reinitialize(h0="h", v0="-0.8*v"))
    system = System("ball")
    system.add_component(ball)
    system.add_event_connection(EventConnection("P", "floor", "P", "bounce"))
    system.initialize(0.0)
    text = system.to_plan()
    assert "\nfmi3_variables 0 " in text and '\nfmi3_variable 0 ' in text
    time, values, events = _run_standalone(text)
    python_time, python_values, python_events = _python_run(system)
    assert len(events) >= 3
    assert events == python_events
    np.testing.assert_array_equal(time, python_time)
    np.testing.assert_array_equal(values, python_values)


CLOCKED_PLAN = """syssimx-plan 1
system "tank and counter"
fmu "Tank" 1 3 "tank" "level_detector" "{token}" "Tank" 0
fmi3_variables 0 1 1
fmi3_variable 0 1 float64 "level"
fmi3_output_clock 0 7
fmu "Counter" 1 3 "counter" "tick_counter" "{token}" "Counter" 0
fmi3_variables 1 1 1
fmi3_triggered_clock 1 3
output_clock_source 0 0
connect_clock output_clock 0 1 0
subscribe output_clock 0 1
"""


def test_the_clock_records_of_the_format_are_read_and_written_back() -> None:
    """The records of FMI 3.0 clocks (output clock sources, clock connections, the clocks of
    an FMU's type table) read and write back; a source not defined before is refused."""
    size = ffi.new("size_t *")
    written = lib().ssx_plan_write(_read(CLOCKED_PLAN), size)
    try:
        assert ffi.string(written, size[0]).decode() == CLOCKED_PLAN
    finally:
        lib().ssx_plan_text_free(written)
    error = ffi.new("char[]", _ERROR_SIZE)
    text = CLOCKED_PLAN.replace("subscribe output_clock 0 1", "subscribe output_clock 1 1")
    assert lib().ssx_plan_read(text.encode(), len(text), error, _ERROR_SIZE) == ffi.NULL
    assert "no output clock source 1 defined before" in ffi.string(error).decode()


def test_a_clock_connection_runs_from_the_plan_as_in_python() -> None:
    """The tank's output clock `full` ticks the counter's triggered clock `tick` (the clocked
    FMUs of test_clock_connections.py): the engine alone counts the same ticks at the same
    times."""
    system = System("tank and counter")
    system.add_component(FMUComponent("Tank", fmus.path("level_detector_fmi3")))
    system.add_component(FMUComponent("Counter", fmus.path("tick_counter_fmi3")))
    system.add_connection(Connection("Tank", "level", "Counter", "signal"))
    system.add_clock_connection("Tank.full", "Counter.tick")
    system.initialize(0.0)
    text = system.to_plan()
    assert "\noutput_clock_source 0 0\nconnect_clock output_clock 0 1 0\n" in text
    time, values, events = _run_standalone(text, component=1)
    python_time, python_values, python_events = _python_run(system, "Counter")
    assert len(events) > 3 and events == python_events
    np.testing.assert_array_equal(time, python_time)
    np.testing.assert_array_equal(values, python_values)


def test_a_clocked_model_exchange_fmu_runs_from_the_plan_as_in_python() -> None:
    """sampled_signal_fmi3 as Model Exchange: its periodic clock is an fmi3_clock record, and
    the engine alone stops at the same ticks, to the bit."""
    system = System("sampled signal")
    system.add_component(FMUComponent("S", fmus.path("sampled_signal_fmi3"),
                                      interface="model-exchange", tolerance=1e-10))
    system.initialize(0.0)
    text = system.to_plan()
    assert "\nfmi3_clock 0 8 0.1 0\n" in text
    time, values, events = _run_standalone(text)
    python_time, python_values, python_events = _python_run(system, "S")
    assert len(events) == round(STOP / 0.1) and events == python_events
    np.testing.assert_array_equal(time, python_time)
    np.testing.assert_array_equal(values, python_values)
