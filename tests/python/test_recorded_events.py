"""A run's event records are copied out of the engine when the run returns and made Python
objects when first asked for: made late, they are still that run's, whatever the System ran
since; read early, they are the same."""

from __future__ import annotations

import pendulum_wall
from syssimx import Reinitialize


def _wall() -> tuple:
    return pendulum_wall.build("euler", "illinois", Reinitialize(theta0="theta", omega0="-omega"))


def test_records_made_after_later_runs_are_the_runs_own() -> None:
    system, pendulum = _wall()
    early = system.run(0.0, 3.0, 0.05)
    expected = list(early.events)  # made now
    statistics = early.statistics
    system.initialize(0.0)
    late = system.run(0.0, 3.0, 0.05)  # not read until the next run has run
    system.initialize(0.0)
    system.run(0.0, 1.0, 0.05)
    assert len(system.history.events) == 1  # the history is the last run's
    assert list(late.events) == expected
    assert late.statistics.iterations_per_event == statistics.iterations_per_event
    # the event column reads them too, and the trials came along
    _, data = late["P"]
    assert int(data["wall_hit"].sum()) == len(expected) == 3
    assert all(len(event.trials) == event.iterations == 2 for event in late.events)
    pendulum.free()


def test_no_event_no_record() -> None:
    system, pendulum = _wall()
    result = system.run(0.0, 0.4, 0.05)  # the first wall hit is at 0.465 s
    assert list(result.events) == [] and system.history.events == []
    assert result.statistics.iterations_per_event == ()
    pendulum.free()
