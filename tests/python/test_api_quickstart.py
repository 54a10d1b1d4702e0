"""The SysSimX quickstart (LinearSource -> Integrator, examples/quickstart.py, its classes as
SysSimX documents them) runs unchanged and gives its number."""

from __future__ import annotations

import numpy as np
import pytest
from quickstart import Integrator, LinearSource
from syssimx import Connection, JacobiAlgorithm, SimulationError, System


def quickstart_system() -> System:
    system = System(name="QuickstartSystem")
    system.add_component(LinearSource(name="LinearSource", a=1.0, b=0.0))
    system.add_component(Integrator(name="Integrator", x0=0.0))
    system.add_connection(Connection(src_comp="LinearSource", src_port="y",
                                     dst_comp="Integrator", dst_port="u"))
    return system


def test_quickstart_gives_12_25_at_t_5():
    # Forward Euler of y' = t with inputs of the step start: sum_{k<50} 0.1 * 0.1k = 12.25,
    # exactly what SysSimX prints for its quickstart.
    system = quickstart_system()
    system.initialize(t0=0.0)
    result = system.run(t0=0.0, tf=5.0, dt=0.1)
    t_vals, data = result["Integrator"]
    assert t_vals[-1] == 5.0
    assert data["y"][-1] == pytest.approx(12.25, abs=1e-12)
    assert len(t_vals) == 51
    assert result.statistics.do_step_calls == 100


def test_quickstart_whole_trajectory_and_jacobi_agree():
    system = quickstart_system()
    system.initialize(0.0)
    _t, data = system.run(0.0, 5.0, 0.1)["Integrator"]
    k = np.arange(51)
    np.testing.assert_allclose(data["y"], 0.01 * k * (k - 1) / 2, atol=1e-12)
    jacobi = quickstart_system()
    jacobi.set_algorithm(JacobiAlgorithm())
    jacobi.initialize(0.0)
    np.testing.assert_allclose(jacobi.run(0.0, 5.0, 0.1)["Integrator"][1]["y"], data["y"],
                               atol=1e-12)


def test_grid_ends_exactly_at_tf():
    system = quickstart_system()
    system.initialize(0.0)
    t, _ = system.run(0.0, 1.0, 0.3)["Integrator"]
    np.testing.assert_allclose(t, [0.0, 0.3, 0.6, 0.9, 1.0], atol=1e-15)
    assert t[-1] == 1.0


def test_runs_continue_from_where_they_stopped():
    system = quickstart_system()
    system.initialize(0.0)
    first = system.run(0.0, 2.5, 0.1)
    t_first, y_first = first["Integrator"][0].copy(), first["Integrator"][1]["y"].copy()
    system.run(2.5, 5.0, 0.1)
    # the first result was copied before the engine recorded again; still the same numbers
    np.testing.assert_array_equal(first["Integrator"][0], t_first)
    np.testing.assert_array_equal(first["Integrator"][1]["y"], y_first)
    t, data = system.get_history()["Integrator"]
    assert t[-1] == 5.0
    assert data["y"][-1] == pytest.approx(12.25, abs=1e-12)


def test_standalone_component_steps_on_its_own():
    integrator = Integrator("Alone", x0=1.0)
    integrator.set_inputs({"u": 2.0})
    integrator.initialize(0.0)
    for k in range(4):
        integrator.do_step(0.25 * k, 0.25)
    t, values = integrator.get_history_arrays()
    np.testing.assert_allclose(t, [0.0, 0.25, 0.5, 0.75, 1.0])
    np.testing.assert_allclose(values["y"], [1.0, 1.5, 2.0, 2.5, 3.0])
    assert integrator.get_outputs()["y"] == pytest.approx(3.0)


class Exploding(Integrator):
    def _do_step_internal(self, t: float, dt: float) -> None:
        if t >= 0.5 - 1e-12:
            raise RuntimeError("boom")
        super()._do_step_internal(t, dt)


def test_exception_in_a_python_step_names_component_and_time_and_keeps_history():
    system = System("S")
    system.add_component(LinearSource("Src"))
    system.add_component(Exploding("Bad"))
    system.add_connection(Connection("Src", "y", "Bad", "u"))
    system.initialize(0.0)
    with pytest.raises(SimulationError, match=r"Bad.*boom.*t=0\.5") as info:
        system.run(0.0, 1.0, 0.1)
    assert info.value.component == "Bad"
    assert info.value.time == pytest.approx(0.5)
    assert isinstance(info.value.__cause__, RuntimeError)
    t, data = system.get_history()["Bad"]
    np.testing.assert_allclose(t, [0.0, 0.1, 0.2, 0.3, 0.4, 0.5], atol=1e-12)
    assert data["y"][-1] == pytest.approx(0.1 * 0.1 * (0 + 1 + 2 + 3 + 4))
