"""Ensemble members and results without a cluster: parameter sets (grid, zip, the command
line's value specifications, Monte Carlo draws), a member run in process, the result views."""

from __future__ import annotations

import numpy as np
import pytest
from fixture_fmus import fmu_path

pytest.importorskip("xarray")
from scipy import stats
from syssimx import ConfigurationError
from syssimx.ensemble import (
    EnsembleResult,
    MemberResult,
    MemberTask,
    parameter_sets,
    parse_values,
    run_member,
)
from syssimx.ensemble.sampling import draw


def test_grid_is_every_combination_first_parameter_slowest() -> None:
    sets = parameter_sets({"P.a": [1, 2], "Q.b": np.array([10.0, 20.0, 30.0])})
    assert sets == [{"P.a": 1, "Q.b": 10.0}, {"P.a": 1, "Q.b": 20.0}, {"P.a": 1, "Q.b": 30.0},
                    {"P.a": 2, "Q.b": 10.0}, {"P.a": 2, "Q.b": 20.0}, {"P.a": 2, "Q.b": 30.0}]
    assert all(type(s["Q.b"]) is float for s in sets)  # numpy scalars unwrapped


def test_zip_takes_the_ith_values_together_and_needs_one_length() -> None:
    assert parameter_sets({"P.a": [1, 2], "P.b": [3, 4]}, mode="zip") == [
        {"P.a": 1, "P.b": 3}, {"P.a": 2, "P.b": 4}]
    with pytest.raises(ConfigurationError,
                       match=r"zip mode needs value lists of one length, got \{'P.a': 2, "
                             r"'P.b': 3\}"):
        parameter_sets({"P.a": [1, 2], "P.b": [3, 4, 5]}, mode="zip")


@pytest.mark.parametrize(("parameters", "mode", "message"), [
    ({"theta0": [1]}, "grid", "a varied parameter is named 'Component.parameter', got 'theta0'"),
    ({"P.a": []}, "grid", "P.a: the list of values is empty"),
    ({"P.a": 0.5}, "grid", "P.a: expected a list of values, got 0.5"),
    ({"P.a": [None]}, "grid", "P.a: values must be numbers, booleans or strings, got NoneType"),
    ({"P.a": [1]}, "cartesian", "ensemble mode must be one of ['grid', 'zip'], got 'cartesian'"),
    ({}, "grid", "an ensemble needs at least one parameter to vary"),
])
def test_bad_parameters_are_named(parameters: dict, mode: str, message: str) -> None:
    with pytest.raises(ConfigurationError) as error:
        parameter_sets(parameters, mode=mode)
    assert str(error.value).startswith(message)


def test_command_line_value_specifications() -> None:
    assert parse_values("0.1:0.5:5") == list(np.linspace(0.1, 0.5, 5))
    assert parse_values("0.5,0.6") == [0.5, 0.6]
    assert parse_values("1, 2") == [1, 2] and type(parse_values("1")[0]) is int
    assert parse_values("true,euler") == [True, "euler"]
    with pytest.raises(ConfigurationError, match="the count must be at least 1"):
        parse_values("0:1:0")
    with pytest.raises(ConfigurationError, match="expected START:STOP:COUNT"):
        parse_values("0:1:2.5")


def test_monte_carlo_draws_in_order_from_one_seeded_generator() -> None:
    distributions = {"P.theta0": stats.uniform(0.2, 0.3),
                     "P.L": lambda generator, n: generator.normal(0.6, 0.01, n)}
    sets = draw(distributions, 4, seed=7)
    generator = np.random.default_rng(7)
    theta0 = stats.uniform(0.2, 0.3).rvs(size=4, random_state=generator)
    length = generator.normal(0.6, 0.01, 4)
    assert [s["P.theta0"] for s in sets] == list(theta0)
    assert [s["P.L"] for s in sets] == list(length)
    assert draw(distributions, 4, seed=7) == sets
    with pytest.raises(ConfigurationError, match=r"P\.x: a distribution is a frozen scipy.stats "
                                                 "distribution or a function"):
        draw({"P.x": 3.0}, 2, seed=0)
    with pytest.raises(ConfigurationError, match=r"P\.x: the distribution gave 3 values for 2 "
                                                 "samples"):
        draw({"P.x": lambda generator, n: [1.0, 2.0, 3.0]}, 2, seed=0)


def refuse() -> None:
    raise ValueError("no system today")


def test_a_member_that_raises_is_a_failed_result_not_an_exception() -> None:
    member = run_member(refuse, MemberTask(3, {"P.theta0": 0.5}, 0.0, 1.0, 0.1))
    assert (member.index, member.status, member.error_type) == (3, "failed", "ValueError")
    assert member.error == "ValueError: no system today"
    assert member.time.size == 0 and member.outputs == {}


def synthetic_members() -> list[MemberResult]:
    """Two members on the grid 0, 0.5, 1: one with an event handled at 0.5 (two samples there)
    and one between grid points; a third failed after its first sample."""
    event_at_grid = MemberResult(
        0, {"P.k": 1.0}, "ok", time=np.array([0.0, 0.5, 0.5, 1.0]),
        micro=np.array([0, 0, 1, 0]), outputs={"P.x": np.array([1.0, 2.0, -2.0, 3.0])},
        events=((0.5, 0, "P.hit"),))
    event_between = MemberResult(
        1, {"P.k": 2.0}, "ok", time=np.array([0.0, 0.25, 0.25, 0.5, 1.0]),
        micro=np.array([0, 0, 1, 0, 0]), outputs={"P.x": np.array([4.0, 5.0, -5.0, 6.0, 7.0])},
        events=((0.25, 0, "P.hit"),))
    failed = MemberResult(2, {"P.k": 3.0}, "failed", "SimulationError: gone", "SimulationError",
                          time=np.array([0.0]), micro=np.array([0]),
                          outputs={"P.x": np.array([8.0])})
    return [event_at_grid, event_between, failed]


def test_dataset_keeps_each_members_own_samples_and_grid_view_the_grid() -> None:
    result = EnsembleResult(synthetic_members(), ["P.k"], 0.0, 1.0, 0.5, 0.0)
    dataset = result.dataset
    assert dict(dataset.sizes) == {"member": 3, "sample": 5, "event": 1}
    assert list(dataset["P.k"].values) == [1.0, 2.0, 3.0]
    np.testing.assert_array_equal(dataset["time"].values[1], [0.0, 0.25, 0.25, 0.5, 1.0])
    np.testing.assert_array_equal(dataset["micro"].values[0], [0, 0, 1, 0, -1])
    np.testing.assert_array_equal(dataset["P.x"].values[2], [8.0] + [np.nan] * 4)
    assert list(dataset["status"].values) == ["ok", "ok", "failed"]
    assert list(dataset["event_time"].values[:, 0][:2]) == [0.5, 0.25]
    grid = result.grid()
    assert list(grid["time"].values) == [0.0, 0.5, 1.0]
    np.testing.assert_array_equal(grid["P.x"].values,
                                  [[1.0, 2.0, 3.0], [4.0, 6.0, 7.0], [8.0, np.nan, np.nan]])


def test_tidy_table_and_events_table(tmp_path) -> None:
    result = EnsembleResult(synthetic_members(), ["P.k"], 0.0, 1.0, 0.5, 0.0)
    table = result.to_dataframe()
    assert len(table) == 4 + 5 + 1
    assert list(table.columns) == ["member", "P.k", "status", "error", "time", "micro", "P.x"]
    assert list(table[table.member == 2].error) == ["SimulationError: gone"]
    assert result.events.to_dict("records") == [
        {"member": 0, "P.k": 1.0, "time": 0.5, "micro": 0, "source": "P.hit"},
        {"member": 1, "P.k": 2.0, "time": 0.25, "micro": 0, "source": "P.hit"}]
    with pytest.raises(ConfigurationError, match=r"unknown result format '.xlsx'; use one of "
                                                 r"\.csv, \.parquet, \.nc"):
        result.write(tmp_path / "out.xlsx")


def test_parquet_without_an_engine_says_what_to_install(tmp_path) -> None:
    pytest.importorskip("pandas")
    try:
        import pyarrow  # noqa: F401
        pytest.skip("pyarrow is installed: parquet is written")
    except ImportError:
        pass
    result = EnsembleResult(synthetic_members(), ["P.k"], 0.0, 1.0, 0.5, 0.0)
    with pytest.raises(ConfigurationError, match="writing parquet needs pyarrow or fastparquet"):
        result.write(tmp_path / "out.parquet")


def test_an_ensemble_without_its_run_or_with_a_system_object_fails_before_starting() -> None:
    from syssimx import System
    from syssimx.ensemble import sweep

    with pytest.raises(ConfigurationError, match=r"the ensemble's run needs tf, dt \(given as "
                                                 r"arguments, or in the system file's 'run' "
                                                 r"entry\)"):
        sweep(refuse, {"P.theta0": [0.1]}, t0=0.0)
    with pytest.raises(ConfigurationError, match="an ensemble needs a function that builds the "
                                                 "System"):
        sweep(System("built"), {"P.theta0": [0.1]}, t0=0.0, tf=1.0, dt=0.1)
    with pytest.raises(ConfigurationError, match="member_timeout must be a positive number of "
                                                 "seconds, got 0"):
        sweep(refuse, {"P.theta0": [0.1]}, t0=0.0, tf=1.0, dt=0.1, member_timeout=0)


def terminating_system():
    from syssimx import FMUComponent, System

    ramp = FMUComponent("R", fmu_path("terminating"))
    system = System("ramp")
    system.add_component(ramp)
    return system


def test_a_member_whose_fmu_asks_to_stop_is_ok_and_says_so() -> None:
    member = run_member(terminating_system, MemberTask(0, {"R.stop_time": 0.3}, 0.0, 1.0, 0.1))
    assert member.ok and member.error == ""
    assert member.termination == "component 'R' asked to stop at t = 0.3"
    assert member.time[-1] == pytest.approx(0.3)
    result = EnsembleResult([member], ["R.stop_time"], 0.0, 1.0, 0.1, 0.0)
    assert list(result.dataset["termination"].values) == [member.termination]
