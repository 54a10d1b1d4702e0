"""Decimation: System.initialize(output_interval=k) keeps every k-th communication point since
t0, System.run(..., output_interval=k*dt) every k-th of that run (FMPy's meaning). Both keep the
end of each run and both samples of every event instant, with the values of the full history,
and hold only the memory those samples need."""

from __future__ import annotations

import numpy as np
import pytest
from syssimx import ConfigurationError, EventConnection, FMUComponent, HybridAlgorithm, System, fmus

INTERVAL = 10


def bounce(component: FMUComponent, event_names: list[str], t: float) -> None:
    outputs = component.get_outputs()
    component.reinitialize(t, theta0=outputs["theta"].magnitude,
                           omega0=-outputs["omega"].magnitude)


def pendulum_against_wall(output_interval: int) -> System:
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.set_parameters(theta0=0.5, omega0=0.0)
    pendulum.add_event_indicator("wall_hit", variable="theta", direction=-1)
    pendulum.add_event_handler("omega_invert", bounce)
    system = System("wall")
    system.add_component(pendulum)
    system.add_event_connection(EventConnection("P", "wall_hit", "P", "omega_invert"))
    system.set_algorithm(HybridAlgorithm(tol_time=1e-9, tol_value=1e-9))
    system.initialize(0.0, output_interval=output_interval)
    return system


def test_decimated_history_is_the_full_one_at_its_grid_points_run_ends_and_events():
    full = pendulum_against_wall(1)
    decimated = pendulum_against_wall(INTERVAL)
    for t0, tf in ((0.0, 1.005), (1.005, 2.0)):
        full.run(t0, tf, 1e-3)
        decimated.run(t0, tf, 1e-3)
    full_t, full_data = full.get_history()["P"]
    t, data = decimated.get_history()["P"]
    event_times = [e.t for e in decimated.history.events]
    assert len(event_times) == 2  # wall hits near 0.465 and 1.395

    kept = []
    grid_point = 0
    for row, time in enumerate(full_t):
        if time in event_times:  # before and after handling
            kept.append(row)
            continue
        if grid_point % INTERVAL == 0 or time in (1.005, 2.0):
            kept.append(row)
        grid_point += 1
    # grid points 0, 10, ..., 2000, the first run's end and two samples per event
    assert len(kept) == 201 + 1 + 2 * 2
    np.testing.assert_array_equal(t, full_t[kept])
    for name in ("theta", "omega", "alpha"):
        np.testing.assert_array_equal(data[name], full_data[name][kept])
    assert decimated.history_bytes() * 5 < full.history_bytes()


def test_an_output_interval_below_one_is_refused_with_the_engine_message():
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    system = System("wall")
    system.add_component(pendulum)
    with pytest.raises(ConfigurationError, match=r"^output_interval: system 'wall': the output "
                       r"interval is a number of grid steps >= 1, not 0$"):
        system.initialize(0.0, output_interval=0)


def test_a_run_interval_keeps_the_full_runs_samples_at_its_own_grid_from_each_run_start():
    full = pendulum_against_wall(1)
    decimated = pendulum_against_wall(1)
    ends = (1.005, 2.0, 2.004)
    for t0, tf in zip((0.0, *ends), ends, strict=False):
        full.run(t0, tf, 1e-3)
        # FMPy's meaning: a time; the last run keeps every point again
        decimated.run(t0, tf, 1e-3, output_interval=None if tf == 2.004 else INTERVAL * 1e-3)
    full_t, full_data = full.get_history()["P"]
    t, data = decimated.get_history()["P"]
    event_times = [e.t for e in decimated.history.events]
    assert len(event_times) == 2

    kept = [0]
    run = 0
    steps_into_run = 0
    for row in range(1, len(full_t)):
        time = full_t[row]
        if time in event_times:  # before and after handling
            kept.append(row)
            continue
        steps_into_run += 1
        if steps_into_run % INTERVAL == 0 or time == ends[run] or run == 2:
            kept.append(row)
        if time == ends[run]:
            run, steps_into_run = run + 1, 0
    # 0.01, ..., 1.0 and 1.005; 1.015, ..., 1.995 and 2.0; 2.001, ..., 2.004; the events twice
    assert len(kept) == 1 + 101 + 100 + 4 + 2 * 2
    # counted from the second run's start, not from t0
    assert np.isclose(t, 1.015).any() and not np.isclose(t, 1.01).any()
    np.testing.assert_array_equal(t, full_t[kept])
    for name in ("theta", "omega", "alpha"):
        np.testing.assert_array_equal(data[name], full_data[name][kept])


def test_a_run_of_a_million_steps_keeping_a_thousand_holds_a_thousandth_of_the_history():
    systems = {}
    for interval in (None, 1000 * 1e-6):
        system = System("ramp")
        system.add_component(FMUComponent("G", fmus.path("gain")))
        system.initialize(0.0)
        result = system.run(0.0, 1.0, 1e-6, output_interval=interval)
        systems[interval] = (len(result.micro), system.history_bytes())
    (full_samples, full_bytes), (kept_samples, kept_bytes) = systems.values()
    assert (full_samples, kept_samples) == (1_000_001, 1_001)
    assert 900 < full_bytes / kept_bytes < 1100


@pytest.mark.parametrize("interval", [0.015, 0.005, 0.0, -0.02])
def test_an_output_interval_that_is_no_whole_multiple_of_dt_is_refused_before_the_run(interval):
    system = pendulum_against_wall(1)
    with pytest.raises(ConfigurationError, match=rf"^wall: output_interval={interval!r} is not a "
                                                 r"whole multiple of dt=0\.01$"):
        system.run(0.0, 1.0, 0.01, output_interval=interval)
    assert system.t == 0.0
    assert len(system.get_history()["P"][0]) == 1
