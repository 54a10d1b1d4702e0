"""FMI 1.0 FMUs run behind the same component.

- libcosim's identity.fmu (FMI 1.0 Co-Simulation, ViProMa's demo FMU) gives FMPy's numbers on
  the same grid; its description is read by the engine's reader.
- The toolchain's FMI 1.0 builds (pendulum_cvode_fmi1, bouncing_ball_cvode_fmi1 and their
  Model Exchange twins *_me, the same model core as the FMI 2.0 builds): Co-Simulation equal to
  FMPy on the same grid and to the FMI 2.0 build; Model Exchange within the integrator's
  tolerance of the exact solution, as FMPy's Model Exchange run is, and bit for bit the FMI 2.0
  build integrated by the engine; the ball bounces at the closed-form times.
- An FMI 1.0 FMU cannot roll back: event indicators, its own or the system's, are a clear
  error at initialize.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from fmpy import simulate_fmu
from samples_root import samples_root
from scipy.special import ellipj, ellipk
from syssimx import Connection, FMUComponent, JacobiAlgorithm, System, TableSource, fmus
from syssimx.errors import ConfigurationError

G = 9.81
# the bundled pendulum with theta0 = 0.5: theta(t) from sin(theta / 2) = k sn(K - w t | k^2)
THETA0, M, L, INERTIA = 0.5, 40.0, 0.6, 20.0
W = np.sqrt(M * G * L / INERTIA)
K_MODULUS = np.sin(THETA0 / 2)
TOLERANCE = 1e-10


def exact_theta(t: np.ndarray) -> np.ndarray:
    sn = ellipj(ellipk(K_MODULUS**2) - W * t, K_MODULUS**2)[0]
    return 2 * np.arcsin(K_MODULUS * sn)

SIGNALS = np.array([(0.0, 0.5, 1, False), (0.25, -1.5, 4, True), (0.55, 2.25, -3, False),
                    (1.0, 8.0, 11, True)],
                   dtype=[("time", np.float64), ("realIn", np.float64),
                          ("integerIn", np.int32), ("booleanIn", np.bool_)])


def identity() -> Path:
    path = samples_root() / "libcosim" / "fmi1" / "identity.fmu"
    if not path.is_file():
        pytest.skip(f"libcosim's FMI 1.0 identity.fmu is absent ({path}): set "
                    "SYSSIMX_SSP_SAMPLES")
    return path


def test_identity_is_read_as_fmi1_cosimulation():
    component = FMUComponent("I", identity())
    assert component.info.standard.name == "FMI 1.0"
    assert component.fmu_interface.name == "co-simulation"
    assert component.fmu_interface.model_identifier == "identity"
    assert not component.can_get_set_state  # FMI 1.0 has no FMU state
    assert {n: s.type.name for n, s in component.input_specs.items()} == {
        "realIn": "REAL", "integerIn": "INT", "booleanIn": "BOOL", "stringIn": "STRING"}
    assert sorted(component.output_specs) == ["booleanOut", "integerOut", "realOut",
                                              "stringOut"]
    # no ModelStructure in FMI 1.0: every output depends on every input
    assert component.direct_feedthrough["realOut"] == {"realIn", "integerIn", "booleanIn",
                                                       "stringIn"}


def test_identity_driven_by_a_table_equals_fmpy():
    """The table drives the identity's discrete inputs (held, as FMPy holds discrete inputs)
    in a Jacobi system: each step starts from the table at its start, as FMPy's input does."""
    path = identity()
    system = System("driven")
    system.add_component(TableSource("u", SIGNALS, hold=["realIn"]))
    system.add_component(FMUComponent("I", path))
    for kind in ("real", "integer", "boolean"):
        system.add_connection(Connection("u", f"{kind}In", "I", f"{kind}In"))
    system.set_algorithm(JacobiAlgorithm())
    system.initialize(0.0)
    t, values = system.run(0.0, 1.2, 0.05)["I"]
    reference = simulate_fmu(str(path), stop_time=1.2, output_interval=0.05, input=SIGNALS,
                             output=["realOut", "integerOut", "booleanOut"])
    np.testing.assert_allclose(t, reference["time"], rtol=0, atol=1e-12)  # FMPy sums steps
    for port in ("realOut", "integerOut", "booleanOut"):
        np.testing.assert_array_equal(values[port], reference[port], err_msg=port)
    assert len(set(values["realOut"].tolist())) == 4  # every row of the table came through


def test_set_inputs_reach_an_fmi1_slave_at_once():
    component = FMUComponent("I", identity())
    component.initialize(0.0)
    component.set_inputs({"realIn": 3.5, "integerIn": -2, "booleanIn": True})
    component.do_step(0.0, 0.1)
    assert component.get_state()["realOut"]["value"] == 3.5
    assert component.get_state()["integerOut"]["value"] == -2
    assert component.get_state()["booleanOut"]["value"] is True


def test_event_indicators_on_an_fmi1_fmu_are_refused_at_initialize():
    component = FMUComponent("I", identity())
    component.add_event_indicator("crossing", variable="realOut", direction=1)
    system = System("hybrid")
    system.add_component(component)
    with pytest.raises(ConfigurationError, match=r"^'I' cannot roll back, which locating "
                       r"events needs \(the system has event indicators\): identity\.fmu is an "
                       r"FMI 1\.0 FMU, and FMI 1\.0 has no FMU state to save and restore$"):
        system.initialize(0.0)


def test_an_fmi1_fmu_beside_a_master_indicator_is_refused_at_initialize():
    ramp = np.array([(0.0, -1.0), (1.0, 1.0)], dtype=[("time", np.float64), ("u", np.float64)])
    table = TableSource("src", ramp)
    table.add_event_indicator("zero", variable="u", direction=1)
    system = System("hybrid")
    system.add_component(table)
    system.add_component(FMUComponent("I", identity()))
    with pytest.raises(ConfigurationError, match=r"'I' cannot roll back.*FMI 1\.0 has no FMU "
                       "state"):
        system.initialize(0.0)


def run_identity(isolated: bool) -> dict[str, np.ndarray]:
    component = FMUComponent("I", identity(), isolated=isolated)
    system = System("identity")
    system.add_component(component)
    system.initialize(0.0)
    component.set_inputs({"realIn": 2.5, "integerIn": 7, "booleanIn": True})
    _, data = system.run(0.0, 1.0, 0.1)["I"]
    return data


def test_identity_runs_isolated_with_the_in_process_values():
    """Reals, integers and booleans (fmiBoolean is a char) cross the host process; string
    variables are no ports of an isolated FMU, as for FMI 2.0."""
    here, there = run_identity(isolated=False), run_identity(isolated=True)
    assert set(there) == {"realOut", "integerOut", "booleanOut"}
    for name in there:
        assert np.array_equal(here[name], there[name]), name
    assert there["realOut"][-1] == 2.5
    assert there["integerOut"][-1] == 7
    assert there["booleanOut"][-1]


def test_cli_simulate_and_info_accept_fmi1(tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    from syssimx.cli import main

    path = str(identity())
    output = tmp_path / "out.csv"
    assert main(["simulate", path, "--stop-time", "0.3", "--step-size", "0.1",
                 "--set", "realIn=2.5", "--set", "integerIn=4", "-o", str(output)]) == 0
    rows = output.read_text().splitlines()
    assert rows[0].split(",")[:3] == ["time", "realOut", "integerOut"]
    assert [row.split(",")[1:3] for row in rows[1:]] == [["2.5", "4"]] * 4
    assert main(["info", path]) == 0
    assert "FMI version:      1.0" in capsys.readouterr().out


def run_alone(component: FMUComponent, stop: float, dt: float) -> tuple[np.ndarray, dict]:
    system = System(component.name)
    system.add_component(component)
    system.initialize(0.0)
    result = system.run(0.0, stop, dt)
    return result[component.name][0], {**result[component.name][1], "events": result.events}


def test_fmi1_cosimulation_build_equals_fmpy_and_the_fmi2_build():
    start = {"theta0": 1.2, "omega0": -0.3, "L": 0.8}
    path = fmus.path("pendulum_cvode_fmi1")
    reference = simulate_fmu(path, stop_time=2.0, output_interval=0.01, start_values=start,
                             output=["theta", "omega", "alpha"])
    runs = {}
    for name in ("pendulum_cvode_fmi1", "pendulum_cvode"):
        component = FMUComponent("P", fmus.path(name))
        component.set_parameters(**start)
        runs[name] = run_alone(component, 2.0, 0.01)
    assert FMUComponent("P", path).info.standard.name == "FMI 1.0"
    t, values = runs["pendulum_cvode_fmi1"]
    np.testing.assert_allclose(t, reference["time"], rtol=0, atol=1e-12)
    for port in ("theta", "omega", "alpha"):
        # the same binary stepped on the same grid: FMPy's numbers
        np.testing.assert_array_equal(values[port], reference[port], err_msg=port)
        # the same model core behind FMI 2.0's entry points
        np.testing.assert_array_equal(values[port], runs["pendulum_cvode"][1][port])


def test_fmi1_model_exchange_follows_the_exact_solution_as_fmpy_does():
    component = FMUComponent("P", fmus.path("pendulum_cvode_fmi1_me"), tolerance=TOLERANCE)
    assert component.model_exchange and component.info.number_of_states == 2
    component.set_parameters(theta0=THETA0)
    t, values = run_alone(component, 1.0, 0.01)
    fmpy_me = simulate_fmu(fmus.path("pendulum_cvode_fmi1_me"), relative_tolerance=TOLERANCE,
                           stop_time=1.0, output_interval=0.01, start_values={"theta0": THETA0},
                           solver="CVode")
    # both integrate with CVODE at relative tolerance 1e-10 (the engine's absolute tolerance:
    # times each state's nominal, 1): over about two quarter periods their global errors stay
    # within 1e-8, the bound the engine's Model Exchange tests hold it to (FMPy's is smaller)
    assert np.abs(values["theta"] - exact_theta(t)).max() < 1e-8
    assert np.abs(fmpy_me["theta"] - exact_theta(fmpy_me["time"])).max() < 10 * TOLERANCE
    np.testing.assert_allclose(t, fmpy_me["time"], rtol=0, atol=1e-12)
    assert np.abs(values["theta"] - fmpy_me["theta"]).max() < 1e-8 + 10 * TOLERANCE
    twin = FMUComponent("P", fmus.path("pendulum_cvode"), tolerance=TOLERANCE,
                        interface="model-exchange")
    twin.set_parameters(theta0=THETA0)
    # the same equations through FMI 2.0's entry points, integrated alike
    np.testing.assert_array_equal(values["theta"], run_alone(twin, 1.0, 0.01)[1]["theta"])


def bounce_times(e: float = 0.8, h0: float = 1.0, count: int = 3) -> list[float]:
    """The ball's bounces from h0 at rest: v := -e v at h = 0."""
    times, t, speed = [], np.sqrt(2 * h0 / G), np.sqrt(2 * G * h0)
    for _ in range(count):
        times.append(float(t))
        speed *= e
        t += 2 * speed / G
    return times


def test_fmi1_model_exchange_ball_bounces_at_the_closed_form_times():
    ball = FMUComponent("B", fmus.path("bouncing_ball_cvode_fmi1_me"), tolerance=1e-12)
    assert ball.info.number_of_event_indicators == 1
    _, values = run_alone(ball, 2.0, 0.01)
    bounces = [event.t for event in values["events"]]
    assert len(bounces) == 3
    # the FMU's own indicator, located by CVODE's root finding without rollback
    assert np.abs(np.array(bounces) - bounce_times()).max() < 1e-9
    twin = FMUComponent("B", fmus.path("bouncing_ball_cvode"), tolerance=1e-12,
                        interface="model-exchange")
    _, twin_values = run_alone(twin, 2.0, 0.01)
    for port in ("h", "v"):
        # the same equations through FMI 1.0's and FMI 2.0's entry points, integrated alike
        np.testing.assert_array_equal(values[port], twin_values[port])
