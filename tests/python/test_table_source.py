"""TableSource: the values of FMPy's input signals, from every kind of table, evaluated in C;
an FMU driven by one gives FMPy's numbers."""

from __future__ import annotations

import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from fmpy import simulate_fmu
from fmpy.simulation import Input
from syssimx import (
    ConfigurationError,
    Connection,
    FMUComponent,
    JacobiAlgorithm,
    System,
    TableSource,
    fmus,
)

# Jumps at 1.0 (twice: three rows share the stamp) and at 2.5; the integer and boolean change
# at rows; the table covers [0.5, 3.0].
SIGNALS = np.array(
    [(0.5, 1.0, 2, False), (1.0, 2.0, 3, False), (1.0, -4.0, 5, True), (1.0, 6.0, 7, True),
     (2.5, 0.0, 7, False), (2.5, 3.0, 9, True), (3.0, 1.5, -2, True)],
    dtype=[("time", np.float64), ("u", np.float64), ("k", np.int32), ("b", np.bool_)])

# Before, at and between the stamps, a hair (below FMPy's 1e-9 relative) off them, after.
PROBES = [0.0, 0.5, 0.75, 1.0 - 1e-12, 1.0, 1.0 + 1e-12, 1.3, 2.5, 2.5 + 2e-10, 2.75, 3.0, 4.0]


def fmpy_value(column: str, t: float, after_event: bool) -> float:
    """FMPy's Input.interpolate for one column; integers and booleans are its discrete inputs."""
    values, _ = Input.interpolate(time=t, t=SIGNALS["time"],
                                  table=np.asarray(SIGNALS[column], dtype=float)[np.newaxis, :],
                                  discrete=column != "u", after_event=after_event)
    return float(values[0])


def table_system(table: TableSource) -> System:
    system = System("table")
    system.add_component(table)
    return system


@pytest.mark.parametrize("probe", PROBES)
def test_values_are_fmpys_before_and_after_the_run_starts(probe: float):
    """At initialization the value on the left of a jump (FMPy's first setting of the inputs),
    at the end of every step the value on its right (what FMPy sets before each doStep)."""
    system = table_system(TableSource("src", SIGNALS))
    system.initialize(probe)
    t, start = system.get_history()["src"]
    for column in ("u", "k", "b"):
        assert float(start[column][0]) == fmpy_value(column, probe, after_event=False), column
    system.initialize(probe - 0.125)
    t, values = system.run(probe - 0.125, probe, 0.125)["src"]
    assert t[-1] == probe
    for column in ("u", "k", "b"):
        assert float(values[column][-1]) == fmpy_value(column, probe, after_event=True), column


def test_column_kinds_ports_and_units():
    table = TableSource("src", SIGNALS, units={"u": "kN*m"})
    assert [(s.name, s.type.name, s.unit) for s in table.output_specs.values()] == [
        ("u", "REAL", "kN*m"), ("k", "INT", None), ("b", "BOOL", None)]
    system = table_system(table)
    system.initialize(0.0)
    _, values = system.run(0.0, 3.0, 0.5)["src"]
    assert values["u"].tolist() == [1.0, 1.0, 6.0, 4.0, 2.0, 3.0, 1.5]
    assert values["k"].tolist() == [2, 2, 7, 7, 7, 9, -2]
    assert values["b"].tolist() == [False, False, True, True, True, True, True]
    assert str(table.get_outputs()["u"].units) == "kilonewton * meter"
    assert table.get_outputs()["k"] == -2


def test_a_held_real_column_steps_at_the_rows():
    table = TableSource("src", SIGNALS, hold=["u"])
    system = table_system(table)
    system.initialize(0.0)
    _, values = system.run(0.0, 3.0, 0.25)["src"]
    expected = [fmpy_value("k", t, True) for t in np.arange(13) * 0.25]  # discrete rules
    held = [float(Input.interpolate(t, SIGNALS["time"], SIGNALS["u"][np.newaxis, :], True,
                                    True)[0][0]) for t in np.arange(13) * 0.25]
    assert values["u"].tolist() == held
    assert values["k"].tolist() == expected


def test_event_times_are_fmpys_input_events():
    """Repeated stamps and the rows where a held column changes: FMPy's findEvents for inputs
    whose variability is discrete (k, b, and u when held)."""
    for hold, discrete in (((), ("k", "b")), (("u",), ("u", "k", "b"))):
        description = SimpleNamespace(modelVariables=[
            SimpleNamespace(name=name, variability="discrete" if name in discrete
                            else "continuous") for name in ("u", "k", "b")])
        theirs = Input.findEvents(SIGNALS, description)
        ours = TableSource("src", SIGNALS, hold=hold).event_times()
        assert ours.tolist() == theirs[np.isfinite(theirs)].tolist()
    assert TableSource("src", SIGNALS).event_times().tolist() == [1.0, 2.5, 3.0]


def test_dataframe_and_fmpy_csv_give_the_same_outputs(tmp_path: Path):
    frame = pd.DataFrame({name: SIGNALS[name] for name in SIGNALS.dtype.names})
    csv_path = tmp_path / "signals.csv"
    csv_path.write_text('"time","u","k","b"\n' + "".join(
        f"{t!r},{u!r},{k},{int(b)}\n" for t, u, k, b in SIGNALS.tolist()))
    runs = []
    for source in (SIGNALS, frame, csv_path, str(csv_path)):
        system = table_system(TableSource("src", source))
        system.initialize(0.0)
        _, values = system.run(0.0, 3.5, 0.25)["src"]
        runs.append({name: np.asarray(v, dtype=float).copy() for name, v in values.items()})
    for column in ("u", "k", "b"):
        np.testing.assert_array_equal(runs[1][column], runs[0][column])
    for run in runs[2:]:
        np.testing.assert_array_equal(run["u"], runs[0]["u"])
        # a CSV holds numbers only: every column is REAL and interpolates (k at 0.75: 2 -> 3)
        assert run["k"][3] == 2.5
    assert TableSource("src", csv_path).output_specs["k"].type.name == "REAL"


def test_a_table_drives_an_fmu_as_fmpy_input_does():
    """A torque table in kN*m drives the bundled pendulum (input torque in N.m) in a Jacobi
    system: each step starts from the table at its start, exactly FMPy's simulate_fmu(input=)."""
    torque = np.array([(0.0, 0.0), (0.4, 0.002), (0.4, -0.001), (1.0, 0.003)],
                      dtype=[("time", np.float64), ("torque", np.float64)])
    system = System("driven")
    system.add_component(TableSource("u", torque, units={"torque": "kN*m"}))
    system.add_component(FMUComponent("P", fmus.path("pendulum_euler")))
    system.add_connection(Connection("u", "torque", "P", "torque"))
    system.set_algorithm(JacobiAlgorithm())
    system.initialize(0.0)
    t, values = system.run(0.0, 1.5, 0.01)["P"]
    in_newton_metres = torque.copy()
    in_newton_metres["torque"] *= 1000.0
    reference = simulate_fmu(fmus.path("pendulum_euler"), stop_time=1.5, output_interval=0.01,
                             input=in_newton_metres, output=["theta", "omega", "alpha"])
    np.testing.assert_array_equal(t, reference["time"])
    for port in ("theta", "omega", "alpha"):
        # the same binary, grid and inputs; kN*m -> N.m multiplies by 1000 (exact here)
        np.testing.assert_allclose(values[port], reference[port], rtol=1e-12, atol=1e-15)
    assert values["omega"][-1] != 0.0


def test_an_event_on_a_table_output_is_located_by_rolling_the_table_back():
    ramp = np.array([(0.0, -1.0), (1.0, 1.0)], dtype=[("time", np.float64), ("u", np.float64)])
    table = TableSource("src", ramp)
    table.add_event_indicator("zero", variable="u", direction=1)
    system = table_system(table)
    system.initialize(0.0)
    system.algorithm.tol_time = 1e-10
    result = system.run(0.0, 1.0, 0.3)
    assert [round(e.t, 9) for e in result.events] == [0.5]
    assert abs(result.events[0].t - 0.5) <= 1e-10


def test_no_python_runs_per_step():
    """The table is evaluated by the engine: a run of 10 000 steps makes exactly as many Python
    calls as a run of 10."""
    def python_calls(steps: int) -> int:
        system = table_system(TableSource("src", SIGNALS))
        system.initialize(0.0)
        calls = 0

        def count(frame, event, arg):
            nonlocal calls
            calls += event == "call"
        sys.setprofile(count)
        try:
            system.run(0.0, 3.0, 3.0 / steps)
        finally:
            sys.setprofile(None)
        return calls

    assert python_calls(10_000) == python_calls(10)


@pytest.mark.parametrize(("table", "message"), [
    (np.array([(0.0, 1.0), (2.0, 2.0), (1.0, 3.0)], dtype=[("t", float), ("u", float)]),
     "table 'src': the time goes back from 2 to 1 in row 2; times must not decrease"),
    (np.array([(0.0, 1.0), (1.0, np.nan)], dtype=[("t", float), ("u", float)]),
     "table 'src': column 0 holds nan in row 1; values must be finite"),
    (np.zeros(0, dtype=[("t", float), ("u", float)]), "table 'src': the table has no rows"),
])
def test_bad_tables_fail_at_initialize_naming_the_table(table: np.ndarray, message: str):
    system = table_system(TableSource("src", table))
    with pytest.raises(ConfigurationError) as error:
        system.initialize(0.0)
    assert message in str(error.value)


def test_bad_sources_fail_at_construction(tmp_path: Path):
    broken = tmp_path / "broken.csv"
    broken.write_text("time,u\n0,1\n1,x\n")
    cases = [
        ([(0.0, 1.0)], "table 'src': a time table is a numpy structured array, a pandas "
                       "DataFrame or the path of a CSV file; got list"),
        (tmp_path / "missing.csv", f"table 'src': no CSV file {str(tmp_path / 'missing.csv')!r}"),
        (broken, f"table 'src': {broken} is not a table in FMPy's CSV format (a header line, "
                 "then one line of numbers per time): could not convert string to float: 'x'"),
        (np.zeros(2, dtype=[("t", float)]), "table 'src': a table is one row per time: a time "
                                            "column, then at least one signal column; got "
                                            "fields ['t']"),
        (np.zeros(2, dtype=[("t", float), ("name", "U4")]), "table 'src': column 'name' has "
                                                             "dtype <U4"),
    ]
    for source, message in cases:
        with pytest.raises(ConfigurationError) as error:
            TableSource("src", source)
        assert message in str(error.value)
    with pytest.raises(ConfigurationError, match="table 'src': hold names no column 'v'"):
        TableSource("src", SIGNALS, hold=["v"])
    with pytest.raises(ConfigurationError, match="column 'k' is INT; only REAL columns take"):
        TableSource("src", SIGNALS, units={"k": "m"})
