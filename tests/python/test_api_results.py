"""Results outlive their System, plot, describe and draw the system."""

from __future__ import annotations

import gc
import sys
from pathlib import Path

import hybrid_pendulum
import numpy as np
import pytest
from syssimx import CoSimComponent, FMUComponent, PortSpec, PortType, System, fmus


def run_and_forget_the_system() -> object:
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.set_parameters(theta0=0.5)
    system = System("short-lived")
    system.add_component(pendulum)
    system.initialize(0.0)
    return system.run(0.0, 0.5, 0.1)


def test_result_stays_valid_after_the_system_is_gone():
    result = run_and_forget_the_system()
    gc.collect()
    t, data = result["P"]
    np.testing.assert_allclose(t, [0.0, 0.1, 0.2, 0.3, 0.4, 0.5], atol=1e-12)
    assert data["theta"][0] == 0.5
    assert np.all(np.diff(data["theta"]) < 0)  # released from rest, it swings down


def test_unknown_component_in_a_result_names_the_known_ones():
    result = run_and_forget_the_system()
    with pytest.raises(KeyError, match=r"'Q'.*\['P'\]"):
        result["Q"]


def test_plot_writes_a_png(tmp_path: Path):
    result = run_and_forget_the_system()
    path = tmp_path / "theta.png"
    result.plot(["P.theta", "P.omega"], path=path)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_seed_system_describes_and_draws_itself():
    system, pendulum = hybrid_pendulum.build("euler")
    report = system.describe()
    assert pendulum.name in report and "wall_hit" in report
    source = hybrid_pendulum.picture(system)
    assert "wall_hit" in source and "omega_invert" in source


class Counter(CoSimComponent):
    """Counts its steps: INT and BOOL outputs, and keeps the times the engine recorded."""

    def __init__(self, name: str):
        super().__init__(name)
        self.output_specs["n"] = PortSpec("n", PortType.INT, "out")
        self.output_specs["odd"] = PortSpec("odd", PortType.BOOL, "out")
        self.recorded: list[float] = []

    def _initialize_component(self, t0: float) -> None:
        self.n = 0

    def _do_step_internal(self, t: float, dt: float) -> None:
        self.n += 1

    def _update_output_states(self, t=None, event_names=None) -> None:
        self.outputs["n"].set(self.n, t)
        self.outputs["odd"].set(self.n % 2 == 1, t)

    def _record_outputs(self, t: float) -> None:
        self.recorded.append(t)


def test_integer_and_boolean_outputs_and_the_record_hook():
    counter = Counter("K")
    system = System("counting")
    system.add_component(counter)
    system.initialize(0.0)
    t, data = system.run(0.0, 0.5, 0.1)["K"]
    assert data["n"].dtype == np.int64 and data["n"].tolist() == [0, 1, 2, 3, 4, 5]
    assert data["odd"].dtype == np.bool_
    assert data["odd"].tolist() == [False, True, False, True, False, True]
    np.testing.assert_allclose(counter.recorded, t, atol=1e-15)
    assert counter.get_outputs() == {"n": 5, "odd": True}


def python_calls_during_run(dt: float) -> int:
    """Python function calls made while a plain FMU with a C indicator runs event-free."""
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.set_parameters(theta0=0.5)
    pendulum.add_event_indicator("rising", variable="theta", direction=1)
    system = System("no python per step")
    system.add_component(pendulum)
    system.initialize(0.0)
    calls = 0

    def count(frame, event, arg) -> None:
        nonlocal calls
        calls += event == "call"

    gc.collect()  # no finalizer of an earlier object may run (and count) during the run
    gc.disable()
    sys.setprofile(count)
    try:
        result = system.run(0.0, 0.4, dt)
    finally:
        sys.setprofile(None)
        gc.enable()
    assert result.events == [] and result.statistics.macro_steps == round(0.4 / dt)
    return calls


def test_declarative_path_runs_no_python_per_step():
    python_calls_during_run(1e-2)  # first use parses cffi types: not part of the comparison
    # ten times the macro steps, not one Python call more
    assert python_calls_during_run(1e-3) == python_calls_during_run(1e-2)
