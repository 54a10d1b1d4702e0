"""Arrays handed to a user keep their samples for their whole life (issue 9, item 1): a
continued run, a new initialize and dropping the System neither change nor free them."""

from __future__ import annotations

import gc

import numpy as np
import pytest
from syssimx import FMUComponent, System, fmus


def pendulum_system() -> System:
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.set_parameters(theta0=0.5, omega0=0.0)
    system = System("history")
    system.add_component(pendulum)
    system.initialize(0.0)
    return system


def test_result_arrays_keep_their_values_through_runs_initialize_and_collection():
    system = pendulum_system()
    t, data = system.run(0.0, 1.0, 0.01)["P"]
    history_t = system.get_history()["P"][0]
    expected_t, expected_theta = t.copy(), data["theta"].copy()
    assert len(t) == 101 and t[-1] == 1.0

    system.run(1.0, 20.0, 0.01)  # grows the history far beyond its first buffers
    np.testing.assert_array_equal(t, expected_t)
    np.testing.assert_array_equal(data["theta"], expected_theta)
    longer_t, longer = system.get_history()["P"]
    assert len(longer_t) == 2001
    np.testing.assert_array_equal(longer["theta"][:101], expected_theta)

    system.initialize(0.0)  # a new history; the old samples belong to their arrays
    system.run(0.0, 0.5, 0.05)
    np.testing.assert_array_equal(t, expected_t)
    np.testing.assert_array_equal(data["theta"], expected_theta)
    np.testing.assert_array_equal(history_t, expected_t)
    assert len(system.get_history()["P"][0]) == 11

    del system
    gc.collect()
    np.testing.assert_array_equal(t, expected_t)
    np.testing.assert_array_equal(data["theta"], expected_theta)
    np.testing.assert_array_equal(longer["theta"][:101], expected_theta)


def test_result_arrays_are_read_only_views_and_copies_are_writable():
    system = pendulum_system()
    t, data = system.run(0.0, 0.1, 0.01)["P"]
    for array in (t, data["theta"], data["omega"]):
        assert not array.flags.writeable
        assert not array.flags.owndata  # a view of the engine's buffers, not a copy
    with pytest.raises(ValueError, match="read-only"):
        data["theta"][0] = 1.0
    theta = data["theta"].copy()
    theta[0] = 1.0
    assert data["theta"][0] == 0.5
