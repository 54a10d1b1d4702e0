"""Results in SysSimX's formats: the tidy long table and the per-component wide table (as data
frames and CSV files), result metadata, SimulationResult.from_system, the system history's CSV
files and trajectories, DenseTime.to_float, __version_info__ and SystemGraphVisualizer."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest
import syssimx
from fmpy.util import plot_result, read_csv, write_csv
from syssimx import ConfigurationError, DenseTime, SimulationResult, System
from syssimx.system.loader import build_system

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def wall_system() -> System:
    """The seed pendulum against a wall: one event (its quarter period), then it swings back."""
    system = build_system(EXAMPLES / "pendulum_wall.yaml")
    system.initialize(0.0)
    return system


@pytest.fixture(scope="module")
def wall() -> tuple[System, SimulationResult]:
    system = wall_system()
    return system, system.run(0.0, 1.0, 0.1)


def test_metadata_as_in_syssimx(wall: tuple[System, SimulationResult]):
    _, result = wall
    assert result.system_name == "pendulum against a wall"
    assert result.algorithm == "HybridAlgorithm"
    assert (result.t0, result.tf, result.dt) == (0.0, 1.0, 0.1)
    assert result.units["P"] == {"theta": "rad", "omega": "rad/s", "alpha": "rad/s2",
                                 "wall_hit": None}
    assert list(result.histories) == ["P"]
    t, ports = result.histories["P"]
    assert np.array_equal(t, result["P"][0]) and list(ports) == list(result["P"][1])
    assert len(t) == 11 + 2  # the grid, and the event instant before and after handling


def test_long_table(wall: tuple[System, SimulationResult]):
    _, result = wall
    frame = result.to_dataframe()
    t, ports = result["P"]
    assert list(frame.columns) == ["component", "port", "time", "micro", "value", "unit"]
    assert len(frame) == 4 * len(t)
    # the event instant's two rows differ by micro: (component, port, time, micro) is a key
    assert frame.pivot(index=["time", "micro"], columns="port", values="value").shape \
        == (len(t), 4)
    event = result.events[0]
    assert frame[(frame["port"] == "theta") & (frame["time"] == event.t)]["micro"].tolist() \
        == [0, 1]
    theta = frame[frame["port"] == "theta"]
    assert theta["time"].tolist() == t.tolist()
    assert theta["value"].tolist() == ports["theta"].tolist()
    assert set(theta["unit"]) == {"rad"} and set(frame["component"]) == {"P"}
    assert frame[frame["port"] == "wall_hit"]["unit"].isna().all()


def test_wide_table_has_units_in_attrs(wall: tuple[System, SimulationResult]):
    _, result = wall
    frame = result.to_dataframe("P")
    assert list(frame.columns) == ["time", "micro", "theta", "omega", "alpha", "wall_hit"]
    assert frame.attrs["units"] == result.units["P"]
    event_at = frame.index[frame["wall_hit"]].tolist()
    assert len(event_at) == 1
    event = result.events[0]
    assert frame["time"][event_at[0]] == event.t == frame["time"][event_at[0] - 1]
    assert frame["micro"][event_at[0]] == 1 and frame["micro"][event_at[0] - 1] == 0


def test_long_csv_reads_back_every_digit(wall: tuple[System, SimulationResult], tmp_path: Path):
    _, result = wall
    path = result.to_csv(tmp_path / "long.csv")
    lines = path.read_text().splitlines()
    t, ports = result["P"]
    assert lines[0] == "component,port,time,micro,value,unit"
    theta = ports["theta"].tolist()
    assert lines[1] == f"P,theta,0.0,0,{theta[0]!r},rad"
    assert lines[2] == f"P,theta,{t.tolist()[1]!r},0,{theta[1]!r},rad"
    assert len(lines) == 1 + 4 * len(t)
    assert lines[-1] == "P,wall_hit,1.0,0,False,"
    loaded = syssimx.system.SystemHistory.load_csv(path)
    assert loaded["P"]["theta"]["unit"] == "rad"
    np.testing.assert_array_equal(loaded["P"]["theta"]["time"], t)
    np.testing.assert_array_equal(loaded["P"]["theta"]["values"], ports["theta"])
    assert loaded["P"]["wall_hit"]["values"].tolist() == ports["wall_hit"].tolist()


def test_wide_csv_is_fmpys_with_units_on_request(wall: tuple[System, SimulationResult],
                                                 tmp_path: Path):
    _, result = wall
    path = result.to_csv(tmp_path / "wide.csv", component="P")
    lines = path.read_text().splitlines()
    t, ports = result["P"]
    assert lines[0] == "time,theta,omega,alpha,wall_hit"
    assert len(lines) == 1 + len(t)  # FMPy's form: the event instant is two rows
    cells = lines[1].split(",")
    assert cells == ["0.0", *(repr(ports[p].tolist()[0]) for p in ("theta", "omega", "alpha")),
                     "0"]
    fmpy_read = read_csv(path)  # FMPy's own reader
    assert fmpy_read.dtype.names == ("time", "theta", "omega", "alpha", "wall_hit")
    np.testing.assert_array_equal(fmpy_read["time"], t)
    np.testing.assert_array_equal(fmpy_read["theta"], ports["theta"])
    np.testing.assert_array_equal(fmpy_read["wall_hit"], ports["wall_hit"])
    with_units = result.to_csv(tmp_path / "units.csv", component="P", units=True)
    assert with_units.read_text().splitlines()[0] \
        == "time,theta [rad],omega [rad/s],alpha [rad/s2],wall_hit"


def test_structured_array_is_taken_by_fmpys_plot_and_writer(
        wall: tuple[System, SimulationResult], tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    _, result = wall
    structured = result.to_structured("P")
    t, ports = result["P"]
    assert structured.dtype.names == ("time", "theta", "omega", "alpha", "wall_hit")
    np.testing.assert_array_equal(structured["time"], t)
    np.testing.assert_array_equal(structured["omega"], ports["omega"])
    # FMPy writes a boolean as False/True, which its reader cannot read: the real columns
    write_csv(tmp_path / "fmpy.csv", structured, columns=["theta", "omega"])
    np.testing.assert_array_equal(read_csv(tmp_path / "fmpy.csv")["theta"], ports["theta"])
    import plotly.graph_objects as go

    shown: list[go.Figure] = []
    monkeypatch.setattr(go.Figure, "show", lambda figure, *args, **kwargs: shown.append(figure))
    plot_result(structured, names=["theta", "omega"], events=True)
    (figure,) = shown
    lines = [trace for trace in figure.data if trace.name in ("theta", "omega")]
    assert [trace.name for trace in lines] == ["theta", "omega"]
    np.testing.assert_array_equal(lines[0].y, ports["theta"])
    everything = result.to_structured()
    assert everything.dtype.names == ("time", "P.theta", "P.omega", "P.alpha", "P.wall_hit")


def test_from_system_equals_the_run_result(wall: tuple[System, SimulationResult]):
    system, result = wall
    rebuilt = SimulationResult.from_system(system, 0.0, 1.0, 0.1)
    assert math.isnan(rebuilt.wall_time)
    assert (rebuilt.system_name, rebuilt.algorithm) == (result.system_name, result.algorithm)
    assert rebuilt.units == result.units
    assert [e.t for e in rebuilt.events] == [e.t for e in result.events]
    assert rebuilt.statistics == result.statistics
    for port, values in result["P"][1].items():
        np.testing.assert_array_equal(rebuilt["P"][1][port], values)


def test_from_system_needs_an_initialized_system():
    with pytest.raises(ConfigurationError, match="empty: nothing recorded yet; call initialize"):
        SimulationResult.from_system(System("empty"), 0.0, 1.0, 0.1)


def test_history_save_csv_and_load_csv(wall: tuple[System, SimulationResult], tmp_path: Path):
    system, result = wall
    path = system.history.save_csv(tmp_path / "nested" / "wide.csv",
                                   port_names={"P": ["theta", "omega"]})
    lines = path.read_text().splitlines()
    assert lines[:2] == ["time,P.theta,P.omega", "s,rad,rad/s"]
    loaded = system.history.load_csv(path)
    t, ports = result["P"]
    assert list(loaded["P"]) == ["theta", "omega"]
    for port in ("theta", "omega"):
        np.testing.assert_array_equal(loaded["P"][port]["time"], t)
        np.testing.assert_array_equal(loaded["P"][port]["values"], ports[port])
    long = system.history.save_csv(tmp_path / "long.csv", long_format=True)
    assert long.read_text() == result.to_csv(tmp_path / "result.csv").read_text()


def test_history_errors_name_what_is_missing(wall: tuple[System, SimulationResult],
                                            tmp_path: Path):
    system, _ = wall
    with pytest.raises(KeyError, match="no component 'Q' in the history; components: \\['P'\\]"):
        system.history.save_csv(tmp_path / "x.csv", component_names=["Q"])
    with pytest.raises(KeyError, match="component 'P' recorded no port 'phi'"):
        system.history.save_csv(tmp_path / "x.csv", port_names={"P": ["phi"]})
    with pytest.raises(ConfigurationError, match="belongs to no initialized system"):
        System("fresh").history.save_csv(tmp_path / "x.csv")
    bad = tmp_path / "bad.csv"
    bad.write_text("a,b\n1,2\n")
    with pytest.raises(ValueError, match=f"{bad}: neither the long layout"):
        system.history.load_csv(bad)


def test_port_trajectory_converts_units(wall: tuple[System, SimulationResult]):
    system, result = wall
    t, theta = system.history.get_port_trajectory("P", "theta")
    np.testing.assert_array_equal(t, result["P"][0])
    np.testing.assert_array_equal(theta, result["P"][1]["theta"])
    _, degrees = system.history.get_port_trajectory("P", "theta", as_unit="deg")
    np.testing.assert_allclose(degrees, np.degrees(theta), rtol=1e-15)
    with pytest.raises(KeyError, match="no component 'Q'"):
        system.history.get_port_trajectory("Q", "theta")


def test_dense_time_and_version_info():
    assert DenseTime(0.25, 3).to_float() == 0.25
    assert syssimx.__version_info__ == tuple(int(p) for p in syssimx.__version__.split("."))
    assert "__version_info__" in syssimx.__all__


@pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz's dot is not installed")
def test_visualizer_from_syssimx_writes_files_as_syssimx(tmp_path: Path):
    from syssimx import SystemGraphVisualizer

    assert "SystemGraphVisualizer" in syssimx.__all__
    SystemGraphVisualizer(wall_system()).visualize(str(tmp_path / "graph.svg"))
    # the suffix is dropped: the picture in the chosen format, the source beside it
    assert sorted(p.name for p in tmp_path.iterdir()) == ["graph", "graph.svg"]
    assert (tmp_path / "graph.svg").read_text().lstrip().startswith("<?xml")
    assert (tmp_path / "graph").read_text().startswith("digraph")


def test_fmpys_csv_reads_back_as_results(tmp_path: Path):
    """A CSV FMPy wrote (quoted names, time first) is read as a result of its file's stem."""
    from fmpy import simulate_fmu

    fmpy_result = simulate_fmu(syssimx.fmus.path("pendulum_euler"), stop_time=0.2,
                               output_interval=0.05)
    write_csv(tmp_path / "Pendulum.csv", fmpy_result)
    assert (tmp_path / "Pendulum.csv").read_text().startswith('"time","theta"')
    loaded = syssimx.system.SystemHistory.load_csv(tmp_path / "Pendulum.csv")
    assert list(loaded) == ["Pendulum"]
    np.testing.assert_array_equal(loaded["Pendulum"]["theta"]["values"], fmpy_result["theta"])
    np.testing.assert_array_equal(loaded["Pendulum"]["omega"]["time"], fmpy_result["time"])
    assert loaded["Pendulum"]["theta"]["unit"] is None
