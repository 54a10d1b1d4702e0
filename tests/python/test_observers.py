"""Observers and streamed runs: System.add_observer's callbacks and System.run(stream_to=...)
see exactly the samples of the in-memory history, bit for bit, in its order (decimated alike),
with the events and localization's restores; keep_history=False keeps them on disk only; a
failing observer stops the run with its exception."""

from __future__ import annotations

import numpy as np
import pytest
from syssimx import (
    ConfigurationError,
    EventConnection,
    FMUComponent,
    HybridAlgorithm,
    SimulationError,
    System,
    fmus,
)

OUTPUTS = ("theta", "omega", "alpha")
COLUMNS = [f"P.{name}" for name in OUTPUTS]
QUARTER_PERIOD = 0.46507759431173046  # the seed pendulum's exact first wall hit


def bounce(component: FMUComponent, event_names: list[str], t: float) -> None:
    outputs = component.get_outputs()
    component.reinitialize(t, theta0=outputs["theta"].magnitude,
                           omega0=-outputs["omega"].magnitude)


def pendulum_against_wall(output_interval: int = 1) -> System:
    pendulum = FMUComponent("P", fmus.path("pendulum_cvode"))
    pendulum.set_parameters(theta0=0.5, omega0=0.0)
    pendulum.add_event_indicator("wall_hit", variable="theta", direction=-1)
    pendulum.add_event_handler("omega_invert", bounce)
    system = System("wall")
    system.add_component(pendulum)
    system.add_event_connection(EventConnection("P", "wall_hit", "P", "omega_invert"))
    system.set_algorithm(HybridAlgorithm(tol_time=1e-10, tol_value=1e-10))
    return system


def history_of(system: System) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(times, micro steps, samples x outputs) of the in-memory history."""
    t, data = system.get_history()["P"]
    micro = system._plan.history().micro()
    values = np.column_stack([np.asarray(getattr(data[n], "magnitude", data[n]), dtype=float)
                              for n in OUTPUTS])
    return np.asarray(t, dtype=float), np.asarray(micro), values


class Recorder:
    def __init__(self) -> None:
        self.columns: list[str] = []
        self.starts: list[float] = []
        self.t: list[float] = []
        self.micro: list[int] = []
        self.values: list[np.ndarray] = []
        self.restores: list[float] = []
        self.events: list[tuple[float, int, str, str]] = []
        self.run_ends = 0

    def start(self, t0: float, columns: list[str]) -> None:
        self.starts.append(t0)
        self.columns = columns

    def step_complete(self, t: float, micro: int, values: np.ndarray) -> None:
        self.t.append(t)
        self.micro.append(micro)
        self.values.append(values)

    def state_restored(self, t: float) -> None:
        self.restores.append(t)

    def event(self, t: float, micro: int, component: str, event: str) -> None:
        self.events.append((t, micro, component, event))

    def run_end(self) -> None:
        self.run_ends += 1


@pytest.mark.parametrize("output_interval", [1, 7])
def test_an_observer_sees_the_history_bit_for_bit(output_interval: int) -> None:
    system = pendulum_against_wall()
    recorder = system.add_observer(Recorder())
    system.initialize(0.0, output_interval=output_interval)
    system.run(0.0, 0.6, 0.01)
    result = system.run(0.6, 1.0, 0.01)
    t, micro, values = history_of(system)
    assert recorder.columns == COLUMNS and recorder.starts == [0.0] and recorder.run_ends == 2
    np.testing.assert_array_equal(np.array(recorder.t), t)
    np.testing.assert_array_equal(np.array(recorder.micro), micro)
    np.testing.assert_array_equal(np.array(recorder.values), values)
    [(event_t, event_micro, component, event)] = recorder.events
    assert (component, event) == ("P", "wall_hit") and event_micro == 0
    assert event_t == system.history.events[0].t
    assert abs(event_t - QUARTER_PERIOD) < 1e-6
    # localization restored the step's start for every trial: the engine's count, at that start
    assert len(recorder.restores) == result.statistics.state_restores > 0
    assert all(0.46 <= r <= event_t for r in recorder.restores)


def test_an_observer_added_after_initialize_starts_with_the_next_run() -> None:
    system = pendulum_against_wall()
    system.initialize(0.0)
    recorder = system.add_observer(Recorder())
    system.run(0.0, 0.1, 0.01)
    assert recorder.starts == [0.0] and len(recorder.t) == 10  # t0 was recorded before it
    system.remove_observer(recorder)
    system.run(0.1, 0.2, 0.01)
    assert len(recorder.t) == 10
    with pytest.raises(ConfigurationError, match="not an observer"):
        system.remove_observer(recorder)
    with pytest.raises(ConfigurationError, match="step_complete"):
        system.add_observer(object())


def test_a_failing_observer_stops_the_run_with_its_exception() -> None:
    class Failing:
        def step_complete(self, t: float, micro: int, values: np.ndarray) -> None:
            if t >= 0.05:
                raise RuntimeError("disk full")

    system = pendulum_against_wall()
    system.add_observer(Failing())
    system.initialize(0.0)
    with pytest.raises(SimulationError, match="disk full") as raised:
        system.run(0.0, 1.0, 0.01)
    assert isinstance(raised.value.__cause__, RuntimeError)
    # the history comes before the observer: it holds the sample that failed
    assert history_of(system)[0][-1] == pytest.approx(0.05)


def read_back(path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(times, micro steps, samples x outputs) of a streamed file, by its suffix."""
    suffix = path.suffix
    if suffix == ".parquet":
        import pyarrow.parquet as pq

        table = pq.read_table(path)
        assert table.column_names == ["time", "micro", *COLUMNS]
        columns = [table.column(name).to_numpy() for name in table.column_names]
    elif suffix == ".csv":
        lines = path.read_text().splitlines()
        assert lines[0].split(",") == ["time", "micro", *COLUMNS]
        data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
        columns = [data[:, k] for k in range(data.shape[1])]
    else:
        import xarray as xr

        with xr.open_dataset(path, engine="scipy") as dataset:
            assert list(dataset.data_vars) == ["time", "micro", *COLUMNS]
            columns = [dataset[name].values for name in ["time", "micro", *COLUMNS]]
    return columns[0], columns[1].astype(int), np.column_stack(columns[2:])


@pytest.mark.parametrize("suffix", [".parquet", ".csv", ".nc"])
def test_a_run_streamed_to_a_file_is_the_history_bit_for_bit(tmp_path, suffix: str) -> None:
    system = pendulum_against_wall()
    system.initialize(0.0)
    path = tmp_path / f"run{suffix}"
    system.run(0.0, 1.0, 0.01, stream_to=path)
    t, micro, values = read_back(path)
    expected_t, expected_micro, expected_values = history_of(system)
    assert len(t) == 101 + 2  # the grid and the event's two instants
    np.testing.assert_array_equal(t, expected_t)
    np.testing.assert_array_equal(micro, expected_micro)
    np.testing.assert_array_equal(values, expected_values)


def test_a_run_without_history_keeps_every_sample_on_disk(tmp_path) -> None:
    reference = pendulum_against_wall(3)
    reference.initialize(0.0, output_interval=3)
    reference.run(0.0, 2.0, 0.01)
    system = pendulum_against_wall(3)
    system.initialize(0.0, output_interval=3)
    path = tmp_path / "run.parquet"
    system.run(0.0, 2.0, 0.01, stream_to=path, keep_history=False)
    assert system.history_bytes() == 0
    for got, expected in zip(read_back(path), history_of(reference), strict=True):
        np.testing.assert_array_equal(got, expected)
    with pytest.raises(ConfigurationError, match="kept no history"):
        system.run(2.0, 3.0, 0.01)
    # initialize again (the engine system is reused): the history keeps samples again
    system.initialize(0.0, output_interval=3)
    system.run(0.0, 2.0, 0.01)
    for got, expected in zip(history_of(system), history_of(reference), strict=True):
        np.testing.assert_array_equal(got, expected)


@pytest.mark.parametrize("suffix", [".parquet", ".csv", ".nc"])
def test_one_writer_object_takes_several_runs(tmp_path, suffix: str) -> None:
    from syssimx.streaming import open_writer

    system = pendulum_against_wall()
    system.initialize(0.0)
    path = tmp_path / f"runs{suffix}"
    writer = open_writer(path)
    writer.open(path, COLUMNS)
    system.run(0.0, 0.3, 0.01, stream_to=writer)
    system.run(0.3, 1.0, 0.01, stream_to=writer)
    writer.close()
    for got, expected in zip(read_back(path), history_of(system), strict=True):
        np.testing.assert_array_equal(got, expected)


def test_an_unknown_format_is_refused_before_the_run(tmp_path) -> None:
    system = pendulum_against_wall()
    system.initialize(0.0)
    with pytest.raises(ConfigurationError, match=r"\.xlsx"):
        system.run(0.0, 1.0, 0.01, stream_to=tmp_path / "run.xlsx")
    assert system.t == 0.0
