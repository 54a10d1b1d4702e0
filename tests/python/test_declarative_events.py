"""Reinitialize: the seed's handler described once and run by the engine. Against the seed's
Python handler on the same FMU: the same event times and samples to the bit, the exact quarter
period, one FMU instance (reset at each event), and no Python call per event. Where Python must
handle the event (a class of the user's, another handler beside it) the same object runs as a
Python handler with the same numbers; YAML's `reinitialize:` entry is the same handler."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pendulum_wall
import pytest
from syssimx import (
    EventConnection,
    FMUComponent,
    HybridAlgorithm,
    Reinitialize,
    System,
    fmus,
)
from syssimx.errors import ConfigurationError
from syssimx.system.loader import run_from_config

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


class Counted(Reinitialize):
    """Counts its calls from Python."""

    calls = 0

    def __call__(self, component: object, event_names: list[str], t: float) -> None:
        Counted.calls += 1
        super().__call__(component, event_names, t)


class UserPendulum(FMUComponent):
    """A class of the user's that handles events itself: Python runs them."""

    def _handle_events_internal(self, event_names: list[str], t: float) -> None:
        super()._handle_events_internal(event_names, t)


def _run(solver: str, handler: object, component: type[FMUComponent] = FMUComponent,
         stop: float = 3.0) -> tuple[list[float], np.ndarray, FMUComponent]:
    pendulum = component("P", fmus.path(f"pendulum_{solver}"))
    pendulum.set_parameters(theta0=0.5, omega0=0.0)
    if solver == "cvode":
        pendulum.set_parameters(cvode_relative_tolerance=1e-10)
    pendulum.add_event_indicator("wall_hit", variable="theta", direction=-1)
    pendulum.add_event_handler("omega_invert", handler)
    system = System("wall")
    system.add_component(pendulum)
    system.add_event_connection(EventConnection("P", "wall_hit", "P", "omega_invert"))
    system.set_algorithm(HybridAlgorithm(tol_time=1e-9, tol_value=1e-9))
    system.initialize(0.0)
    result = system.run(0.0, stop, 0.05)
    return [e.t for e in result.events], result["P"][1]["theta"].copy(), pendulum


@pytest.mark.parametrize("solver", ["cvode", "euler"])
def test_the_engine_runs_the_seeds_handler_with_the_seeds_numbers(solver: str) -> None:
    Counted.calls = 0
    times, theta, pendulum = _run(solver, Counted(theta0="theta", omega0="-omega"))
    assert Counted.calls == 0  # no Python per event
    seed_times, seed_theta, seed = _run(solver, pendulum_wall.bounce)
    assert len(times) == 3
    assert times == seed_times and np.array_equal(theta, seed_theta)
    assert abs(times[0] - pendulum_wall.QUARTER_PERIOD) < (1e-9 if solver == "cvode" else 3e-6)
    counters = pendulum.instance.counters()
    assert (counters["instantiate"], counters["reset"]) == (1, 3)  # initialize was the first
    pendulum.free()
    seed.free()


def test_python_runs_it_where_the_class_handles_events() -> None:
    Counted.calls = 0
    times, theta, pendulum = _run("euler", Counted(theta0="theta", omega0="-omega"),
                                  UserPendulum)
    assert Counted.calls == 3
    engine_times, engine_theta, other = _run("euler", Reinitialize(theta0="theta",
                                                                   omega0="-omega"))
    assert times == engine_times and np.array_equal(theta, engine_theta)
    pendulum.free()
    other.free()


def test_constants_and_gains() -> None:
    """A damped bounce: omega0 = -0.5*omega, and theta0 a constant 0 (the wall)."""
    times, theta, pendulum = _run("euler", Reinitialize(theta0=0.0, omega0="-0.5*omega"),
                                  stop=2.0)
    python_times, python_theta, other = _run(
        "euler", lambda c, names, t: c.reinitialize(
            t, theta0=0.0, omega0=-0.5 * float(c.outputs["omega"].raw())), stop=2.0)
    assert times == python_times and np.array_equal(theta, python_theta)
    assert len(times) == 2
    assert 0.2 < np.max(theta[theta.size // 2:]) < 0.3  # the swing after a bounce: about half
    pendulum.free()
    other.free()


def test_a_wrong_name_is_refused_before_the_run() -> None:
    with pytest.raises(ConfigurationError, match="'P' has no parameter 'theta_0'"):
        _run("euler", Reinitialize(theta_0="theta"))
    with pytest.raises(ConfigurationError, match="'thetas' is not an output of 'P'"):
        _run("euler", Reinitialize(theta0="thetas"))


def test_yaml_reinitialize_is_the_engines_handler() -> None:
    """examples/pendulum_wall.yaml (CVODE, 1 s): the same events as the handler in Python."""
    result = run_from_config(EXAMPLES / "pendulum_wall.yaml")
    times, theta, pendulum = _run("cvode", Reinitialize(theta0="theta", omega0="-omega"),
                                  stop=1.0)
    assert [e.t for e in result.events] == times
    assert np.array_equal(result["P"][1]["theta"], theta)
    assert abs(times[0] - pendulum_wall.QUARTER_PERIOD) < 1e-9
    pendulum.free()
