"""A plan built by the engine alone (ssx_plan_build loading the FMU from its unpacked folder,
ssx_plan_initialize) runs to the same history, bit for bit, as the system Python builds: the
seed's pendulum against a wall (examples/pendulum_wall.yaml), and a pendulum driven by a table
with a jump through a connection."""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np
from syssimx import System, fmus
from syssimx.components.fmu import FMUComponent
from syssimx.components.table_source import TableSource
from syssimx.engine import ffi, lib
from syssimx.system.connection import Connection
from syssimx.system.loader import build_system

ROOT = Path(__file__).resolve().parents[2]

# What Python's System sets up for examples/pendulum_wall.yaml, as plan records: the three
# parameters written in initialization mode (theta0, omega0, cvode_relative_tolerance), the
# outputs theta, omega, alpha, the torque input left to the FMU, the indicator on theta with
# its slope der(theta), the restart with omega reversed, the default algorithm options.
SEED_PLAN = """syssimx-plan 1
system "pendulum against a wall"
experiment 0 1 0.05
fmu "P" 1 2 "pendulum_cvode" "pendulum_cvode" "{e4eeb2ef-23e1-5e9f-4db4-f873308f2419}" "P" 0
fmu_experiment 0 0 0 0 0
start 0 real 7 0.5
start 0 real 8 0
start 0 real 11 1e-10
output 0 real 0
output 0 real 1
output 0 real 2
input 0 real 4 nan
directional_derivatives 0 1
interpolation 0 1 1
indicator_output 0 0 -1
indicator_slope 0 3
subscribe indicator 0 0
restart_handler 0 0 0 0 0 1 11 1e-10 0 0 2 7 0 1 0 8 1 -1 0
hybrid_options 1e-09 1e-09 100 10 0 illinois 0
"""


# A table (a jump at 0.5 s) driving the pendulum's torque, as Python's System sets it up: the
# table's column, the connection, and the schedule Python finds (the pendulum first: its
# outputs do not depend on the torque directly).
TABLE_PLAN = """syssimx-plan 1
system "table drives pendulum"
table "T" 4 0 0.5 0.5 1
table_column 0 real 0 4 0 2 -1 0.5
fmu "P" 1 2 "pendulum_cvode" "pendulum_cvode" "{e4eeb2ef-23e1-5e9f-4db4-f873308f2419}" "P" 0
start 1 real 7 0.5
start 1 real 11 1e-10
output 1 real 0
output 1 real 1
output 1 real 2
input 1 real 4 nan
directional_derivatives 1 1
interpolation 1 1 1
connect 0 0 1 0 1 0
schedule 2 1 0 1 1 0 0
"""


def _unpacked_pendulum(base: Path) -> None:
    with zipfile.ZipFile(fmus.path("pendulum_cvode")) as archive:
        archive.extractall(base / "pendulum_cvode")


def _run_plan(text: bytes, base: Path, component: int = 0
              ) -> tuple[np.ndarray, np.ndarray, list[float]]:
    engine = lib()
    error = ffi.new("char[1024]")
    plan = ffi.gc(engine.ssx_plan_read(text, len(text), error, 1024), engine.ssx_plan_free)
    assert plan != ffi.NULL, ffi.string(error).decode()
    system = engine.ssx_plan_build(plan, str(base).encode(), ffi.NULL, 0, error, 1024)
    assert system != ffi.NULL, ffi.string(error).decode()
    system = ffi.gc(system, engine.ssx_system_free)
    for status in (engine.ssx_plan_initialize(system, plan, 0.0),
                   engine.ssx_run(system, 0.0, 1.0, 0.05)):
        assert status == 0, ffi.string(engine.ssx_last_error(system).message).decode()
    n = engine.ssx_history_length(system)
    time = np.frombuffer(ffi.buffer(engine.ssx_history_time(system), 8 * n), np.float64).copy()
    values = np.frombuffer(ffi.buffer(engine.ssx_history_values(system, component), 24 * n),
                           np.float64).reshape(n, 3).copy()
    record = ffi.new("ssx_event_record *")
    events = [record.t for k in range(engine.ssx_event_count(system))
              if engine.ssx_event_get(system, k, record) == 0]
    return time, values, events


def test_plan_built_without_python_runs_the_seed_as_python_does(tmp_path: Path) -> None:
    _unpacked_pendulum(tmp_path)
    time, values, events = _run_plan(SEED_PLAN.encode(), tmp_path)

    system = build_system(ROOT / "examples" / "pendulum_wall.yaml")
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.05)
    python_time, columns = result.histories["P"]
    python_values = np.column_stack([columns[name] for name in ("theta", "omega", "alpha")])

    assert np.array_equal(time, python_time)
    assert np.array_equal(values, python_values)
    assert events == [event.t for event in result.events]
    assert abs(events[0] - 0.46507759431173046) < 1e-9  # the quarter period


def test_plan_with_a_table_runs_as_python_does(tmp_path: Path) -> None:
    _unpacked_pendulum(tmp_path)
    time, values, _ = _run_plan(TABLE_PLAN.encode(), tmp_path, component=1)

    table = np.array([(0.0, 0.0), (0.5, 2.0), (0.5, -1.0), (1.0, 0.5)],
                     dtype=[("time", float), ("torque", float)])
    system = System("table drives pendulum")
    system.add_component(TableSource("T", table, units={"torque": "N.m"}))
    pendulum = FMUComponent("P", fmus.path("pendulum_cvode"))
    pendulum.set_parameters(theta0=0.5, cvode_relative_tolerance=1e-10)
    system.add_component(pendulum)
    system.add_connection(Connection("T", "torque", "P", "torque"))
    system.initialize(0.0)
    python_time, columns = system.run(0.0, 1.0, 0.05).histories["P"]

    assert np.array_equal(time, python_time)
    assert np.array_equal(values, np.column_stack([columns[name]
                                                   for name in ("theta", "omega", "alpha")]))


def test_written_plan_reads_back_to_the_same_text() -> None:
    engine = lib()
    error = ffi.new("char[1024]")
    plan = ffi.gc(engine.ssx_plan_read(SEED_PLAN.encode(), len(SEED_PLAN), error, 1024),
                  engine.ssx_plan_free)
    size = ffi.new("size_t *")
    text = ffi.gc(engine.ssx_plan_write(plan, size), engine.ssx_plan_text_free)
    assert ffi.string(text, size[0]).decode() == SEED_PLAN
