"""Declarative systems (YAML and JSON, SysSimX's schema plus syssimx's FMU entries) give the
numbers of the same systems built in Python."""

from __future__ import annotations

import json
from pathlib import Path

import coupled_pendulums
import numpy as np
import pytest
import yaml
from syssimx import (
    Connection,
    FMUComponent,
    GaussSeidelAlgorithm,
    HybridAlgorithm,
    IJCSAAlgorithm,
    System,
    fmus,
)
from syssimx.system.loader import build_system, load_config, run_from_config

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
QUARTER_PERIOD = 0.46507759431173046  # theta0 = 0.5: K(sin^2(theta0/2)) / sqrt(m g L / I)


def as_json(tmp_path: Path, name: str) -> Path:
    """The example description `name`.yaml written as JSON (the same mapping)."""
    config = yaml.safe_load((EXAMPLES / f"{name}.yaml").read_text())
    target = tmp_path / f"{name}.json"
    target.write_text(json.dumps(config))
    return target


@pytest.mark.parametrize("file", ["quickstart.yaml", "quickstart.json"])
def test_quickstart_description_gives_12_25_at_t_5(file: str):
    result = run_from_config(EXAMPLES / file, allowed_modules=["quickstart"])
    t, data = result["Integrator"]
    assert len(t) == 51 and t[-1] == 5.0
    assert data["y"][-1] == pytest.approx(12.25, abs=1e-12)


def test_quickstart_yaml_and_json_describe_the_same_system():
    assert load_config(EXAMPLES / "quickstart.yaml") == {
        **load_config(EXAMPLES / "quickstart.json"),
        "connections": [{"src": "LinearSource.y", "dst": "Integrator.u"}]}


def test_run_arguments_override_the_run_entry():
    result = run_from_config(EXAMPLES / "quickstart.yaml", tf=2.0, dt=0.5,
                             allowed_modules=["quickstart"])
    t, data = result["Integrator"]
    # Euler of y' = t with h = 0.5: 0.5 * (0 + 0.5 + 1.0 + 1.5) = 1.5
    assert list(t) == [0.0, 0.5, 1.0, 1.5, 2.0]
    assert data["y"][-1] == pytest.approx(1.5, abs=1e-15)


@pytest.mark.parametrize("form", ["yaml", "json"])
def test_coupled_fmus_match_the_python_built_system(tmp_path: Path, form: str):
    path = EXAMPLES / "coupled_pendulums.yaml" if form == "yaml" \
        else as_json(tmp_path, "coupled_pendulums")
    declared = run_from_config(path)
    python_built = coupled_pendulums.build(GaussSeidelAlgorithm())
    python_built.initialize(0.0)
    reference = python_built.run(0.0, 2.0, 0.01)
    for name in ("P1", "P2", "Spring"):
        t, values = declared[name]
        t_ref, values_ref = reference[name]
        np.testing.assert_array_equal(t, t_ref)
        assert set(values) == set(values_ref)
        for port, column in values.items():
            np.testing.assert_allclose(column, values_ref[port], rtol=0, atol=1e-12)
    assert declared.statistics.do_step_calls == reference.statistics.do_step_calls == 3 * 200


@pytest.mark.parametrize("form", ["yaml", "json"])
def test_pendulum_against_the_wall_declared_in_the_file(tmp_path: Path, form: str):
    path = EXAMPLES / "pendulum_wall.yaml" if form == "yaml" \
        else as_json(tmp_path, "pendulum_wall")
    system = build_system(path)
    assert isinstance(system.algorithm, HybridAlgorithm)
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.05)
    assert len(result.events) == 1
    assert result.events[0].t == pytest.approx(QUARTER_PERIOD, abs=1e-9)
    # the handler restarted the FMU from its outputs with the velocity reversed
    t, values = result["P"]
    before, handled = np.flatnonzero(t == result.events[0].t)
    assert list(result.micro[[before, handled]]) == [0, 1]
    assert values["omega"][before] < 0
    assert values["omega"][handled] == -values["omega"][before]
    assert values["theta"][handled] == values["theta"][before]
    assert np.all(values["theta"][t > result.events[0].t] > 0)


def test_a_description_mapping_builds_without_a_file():
    system = build_system({
        "system": {"name": "loop"},
        "components": [{"name": "PI", "fmu": "pi_controller",
                        "parameters": {"kp": 0.5, "ki": 1.0, "integral0": 1.0}},
                       {"name": "Gain", "fmu": "gain", "parameters": {"k": 0.5}}],
        "connections": [{"src": "PI.u", "dst": "Gain.u"},
                        {"src": {"component": "Gain", "port": "y"},
                         "dst": {"component": "PI", "port": "measurement"}}],
        "algorithm": {"type": "ijcsa", "max_iter": 20, "tol": 1e-12}})
    assert isinstance(system, System)
    assert isinstance(system.algorithm, IJCSAAlgorithm)
    assert (system.algorithm.max_iter, system.algorithm.tolerance) == (20, 1e-12)
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.1)
    # the algebraic loop holds at every sample: u = ki I / (1 + kp k), y = k u
    np.testing.assert_allclose(result["Gain"][1]["y"], 0.5 * result["PI"][1]["u"], atol=1e-12)


def test_an_input_held_at_a_constant_equals_the_python_built_system(tmp_path: Path):
    """`inputs: {setpoint: 2}` holds the unconnected input as set_inputs does, while the
    measurement follows the plant (an algebraic loop: u = kp e + ki integral(e))."""
    path = tmp_path / "held.yaml"
    path.write_text(
        "components:\n"
        "  - {name: PI, fmu: pi_controller, parameters: {kp: 0.5, ki: 2.0},\n"
        "     inputs: {setpoint: 2.0}}\n"
        "  - {name: Plant, fmu: gain, parameters: {k: 0.25}}\n"
        "connections:\n"
        "  - {src: PI.u, dst: Plant.u}\n"
        "  - {src: Plant.y, dst: PI.measurement}\n"
        "run: {t0: 0, tf: 1, dt: 0.1}\n")
    declared = run_from_config(path)
    python_built = System("held")
    controller = FMUComponent("PI", fmus.path("pi_controller"))
    controller.set_parameters(kp=0.5, ki=2.0)
    controller.set_inputs({"setpoint": 2.0})
    plant = FMUComponent("Plant", fmus.path("gain"))
    plant.set_parameters(k=0.25)
    for component in (controller, plant):
        python_built.add_component(component)
    python_built.add_connection(Connection("PI", "u", "Plant", "u"))
    python_built.add_connection(Connection("Plant", "y", "PI", "measurement"))
    python_built.initialize(0.0)
    reference = python_built.run(0.0, 1.0, 0.1)
    for name, port in (("PI", "u"), ("Plant", "y")):
        np.testing.assert_array_equal(declared[name][1][port], reference[name][1][port])
    # the held setpoint drives the loop: at t = 0, u = kp (2 - k u), so u = 2 kp / (1 + kp k)
    assert declared["PI"][1]["u"][0] == pytest.approx(2 * 0.5 / (1 + 0.5 * 0.25), abs=1e-12)


def test_hybrid_options_and_coupling_from_the_file(tmp_path: Path):
    config = load_config(EXAMPLES / "pendulum_wall.yaml")
    config["algorithm"] = {"type": "hybrid", "tol_time": 1e-9, "method": "bisection",
                           "sign_tolerance": 1e-12, "max_deferrals": 0,
                           "raise_on_missed_event": True,
                           "gauss_seidel_algorithm": {"type": "jacobi", "tolerance": 1e-8}}
    system = build_system(config)
    algorithm = system.algorithm
    assert isinstance(algorithm, HybridAlgorithm)
    assert (algorithm.method, algorithm.sign_tolerance, algorithm.max_deferrals,
            algorithm.raise_on_missed_event) == ("bisection", 1e-12, 0, True)
    assert algorithm.coupling.name == "Jacobi" and algorithm.coupling.tolerance == 1e-8


def test_a_class_from_a_module_beside_the_description(tmp_path: Path):
    (tmp_path / "my_blocks_beside.py").write_text(
        "from syssimx import CoSimComponent, PortSpec, PortType\n\n\n"
        "class Clock(CoSimComponent):\n"
        "    def __init__(self, name, rate=1.0):\n"
        "        super().__init__(name)\n"
        "        self.rate = rate\n"
        "        self.output_specs['t'] = PortSpec('t', PortType.REAL, 'out')\n\n"
        "    def _do_step_internal(self, t, dt):\n"
        "        pass\n\n"
        "    def _update_output_states(self, t=None, event_names=None):\n"
        "        self.outputs['t'].set(self.rate * (t or 0.0), t)\n")
    path = tmp_path / "clock.yaml"
    path.write_text("components:\n  - {name: C, class: 'my_blocks_beside:Clock', "
                    "args: {rate: 3.0}}\nrun: {t0: 0, tf: 1, dt: 0.25}\n")
    t, values = run_from_config(path, allowed_modules=["my_blocks_beside"])["C"]
    np.testing.assert_array_equal(values["t"], 3.0 * t)


def test_a_bounce_with_restitution_written_in_the_file():
    """reinitialize: {v0: -0.8*v}: the continuous ball bounces at the closed-form times."""
    g, h0, e = 9.81, 1.0, 0.8
    system = build_system({
        "components": [{
            "name": "Ball", "fmu": "bouncing_ball_continuous_cvode",
            "parameters": {"h0": h0, "v0": 0.0, "g": g, "cvode_relative_tolerance": 1e-12},
            "event_indicators": [{"name": "floor", "variable": "h", "direction": "falling"}],
            "event_handlers": [{"input": "bounce", "reinitialize": {"h0": "h", "v0": "-0.8*v"}}],
        }],
        "event_connections": [{"src": "Ball.floor", "dst": "Ball.bounce"}],
        "algorithm": {"type": "hybrid", "tol_time": 1e-10}})
    system.initialize(0.0)
    result = system.run(0.0, 2.0, 0.01)
    t1 = (2 * h0 / g) ** 0.5
    flights = [2 * e**k * g * t1 / g for k in range(1, 4)]
    expected = np.cumsum([t1, *flights])
    np.testing.assert_allclose([ev.t for ev in result.events], expected[expected < 2.0],
                               rtol=0, atol=1e-8)
