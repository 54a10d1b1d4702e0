"""Decimation (System.initialize(output_interval=k)): the history keeps every k-th
communication point, the end of each run and both samples of every event instant, with the
values of the full history, and holds only the memory those samples need."""

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
