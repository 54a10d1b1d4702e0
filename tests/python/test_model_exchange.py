"""Our own FMUs run as Model Exchange: the engine integrates them with CVODE.

- The seed scenario with pendulum_cvode as Model Exchange gives the exact wall-hit time.
- bouncing_ball bounces at the closed-form times through its own event indicator, without
  rollback; without a rest threshold it chatters, and the run ends with a Zeno error.
- The coupled pendulums (torsion spring) give the Co-Simulation build's numbers under Jacobi
  and Gauss-Seidel: a Model Exchange component is stepped like any other.
- A step taken again after a restore is the first one, bit for bit.
- `interface=` from Python, the command line and the YAML loader, and its errors.
"""

from __future__ import annotations

import re
import zipfile
from pathlib import Path

import coupled_pendulums
import numpy as np
import pytest
from scipy.special import ellipk
from syssimx import (
    ConfigurationError,
    EventConnection,
    FMUComponent,
    FMUError,
    GaussSeidelAlgorithm,
    JacobiAlgorithm,
    System,
    ZenoError,
    fmus,
)
from syssimx.cli import main
from syssimx.engine import ffi, lib
from syssimx.system.loader import build_system

G = 9.81
M, L, INERTIA, THETA0 = 40.0, 0.6, 20.0, 0.5
# the seed's exact first wall hit: the quarter period of the free pendulum
EXACT_WALL_HIT = float(ellipk(np.sin(THETA0 / 2) ** 2) / np.sqrt(M * G * L / INERTIA))


def bounce_times(e: float = 0.8, gap_tol: float = 1e-6, h0: float = 1.0) -> list[float]:
    """bouncing_ball's bounces: from h0 at rest, v := -e v at h = 0, at rest once a rebound
    would rise less than gap_tol."""
    times, t, speed = [], np.sqrt(2 * h0 / G), np.sqrt(2 * G * h0)
    while True:
        times.append(float(t))
        speed *= e
        if speed**2 <= 2 * G * gap_tol:
            return times
        t += 2 * speed / G


def ball(name: str = "B", tolerance: float = 1e-12, **parameters: float) -> FMUComponent:
    component = FMUComponent(name, fmus.path("bouncing_ball_cvode"), interface="model-exchange",
                             tolerance=tolerance)
    component.set_parameters(**parameters)
    return component


def one(component: FMUComponent) -> System:
    system = System(component.name)
    system.add_component(component)
    system.initialize(0.0)
    return system


def test_seed_scenario_as_model_exchange_hits_the_wall_at_the_exact_time():
    """The seed scenario (README form: an indicator on theta, a handler that restarts the FMU
    with omega reversed) with the pendulum integrated by the engine. pendulum_cvode declares no
    event indicator of its own: wall_hit is the master's, located by rollback (its ME steps
    are repeated from the engine's snapshots); the FMU's own events would need none."""
    pendulum = FMUComponent("P", fmus.path("pendulum_cvode"), interface="model-exchange",
                            tolerance=1e-12)
    pendulum.set_parameters(theta0=THETA0, omega0=0.0)
    pendulum.add_event_indicator("wall_hit", variable="theta", direction=-1)
    pendulum.add_event_handler("omega_invert", lambda comp, events, t: comp.reinitialize(
        t, theta0=comp.get_outputs()["theta"].magnitude,
        omega0=-comp.get_outputs()["omega"].magnitude))
    system = System("wall")
    system.add_component(pendulum)
    system.add_event_connection(EventConnection("P", "wall_hit", "P", "omega_invert"))
    system.initialize(t0=0.0)
    system.algorithm.tol_time = 1e-9
    result = system.run(0.0, 1.0, 0.05)
    assert [(e.component, e.event, e.own) for e in result.events] == [("P", "wall_hit", False)]
    assert abs(result.events[0].t - EXACT_WALL_HIT) < 1e-9
    assert result.statistics.own_events == 0
    assert result.statistics.state_restores == result.events[0].rollbacks > 0
    assert np.all(result["P"][1]["theta"] > -1e-9)  # reflected at the wall


def test_pendulum_with_its_own_wall_as_model_exchange_hits_it_at_the_exact_time():
    """The seed's wall as the model's own event indicator (pendulum_contact): integrated by the
    engine, the impact is a root of CVODE, found at the seed's exact time with no rollback."""
    pendulum = FMUComponent("P", fmus.path("pendulum_contact_cvode"),
                            interface="model-exchange", tolerance=1e-12)
    pendulum.set_parameters(theta0=THETA0, omega0=0.0, restitution=1.0)
    system = one(pendulum)
    result = system.run(0.0, 1.0, 0.05)
    impact = result.events[0]
    assert (impact.component, impact.event, impact.micro, impact.own) == (
        "P", "state_event", 0, True)
    assert abs(impact.t - EXACT_WALL_HIT) < 1e-9
    assert result.statistics.state_restores == 0 and result.statistics.state_saves == 0
    assert np.all(result["P"][1]["theta"] > -1e-9)  # reflected at the wall


def test_bouncing_ball_bounces_at_the_closed_form_times_without_rollback():
    system = one(ball())
    result = system.run(0.0, 3.0, 0.01)
    expected = [t for t in bounce_times() if t < 3.0]
    assert len(result.events) == len(expected) == 6
    assert np.max(np.abs(np.array([e.t for e in result.events]) - expected)) < 1e-8
    assert {(e.component, e.event, e.micro, e.own) for e in result.events} == {
        ("B", "state_event", 0, True)}
    assert system.history.get_all_event_histories()[("B", "state_event")][0].micro == 0
    statistics = result.statistics
    assert (statistics.own_events, statistics.state_restores, statistics.do_step_calls) == (
        6, 0, 300)


@pytest.mark.parametrize(("given", "error_bound"), [
    ({"component": 1e-10}, 1e-9), ({"system": 1e-10}, 1e-9), ({}, 1e-5)])
def test_the_integrator_takes_the_tolerance_the_instance_is_set_up_with(given, error_bound):
    """FMUComponent's tolerance=, else System.initialize's, else the engine's default (FMPy's
    1e-5; bouncing_ball has no DefaultExperiment tolerance): the fall before the first bounce
    is as accurate as asked, and no more."""
    component = FMUComponent("B", fmus.path("bouncing_ball_cvode"), interface="model-exchange",
                             tolerance=given.get("component"))
    system = System("ball")
    system.add_component(component)
    system.initialize(0.0, tolerance=given.get("system"))
    t, values = system.run(0.0, 0.45, 0.01)["B"]
    error = np.max(np.abs(values["h"] - (1 - G * t**2 / 2)))
    assert error_bound / 1000 < error < error_bound


def test_a_ball_that_never_rests_ends_with_a_zeno_error():
    """Without a rest threshold the bounces accumulate at a finite time (sum of the flights:
    4.0637 s). By the master's rule for its own indicators, a crossing within ten times
    tol_time of the previous one is chattering: the run ends there, before CVODE, unable to
    resolve the shrinking flights, would let the ball sink through the floor."""
    system = one(ball(gap_tol=0.0))
    with pytest.raises(ZenoError, match=r"^component 'B': its event indicator 0 crossed again at "
                       r"t=4\.0637\d+, only \S+ after its previous crossing: chattering \(Zeno\) "
                       r"behaviour; the minimum interval is 1e-08$"):
        system.run(0.0, 5.0, 0.01)
    t, _ = system.get_history()["B"]
    assert t[-1] == pytest.approx(4.06, abs=0.01)  # the samples before the failure stay


@pytest.mark.parametrize("algorithm", [JacobiAlgorithm, GaussSeidelAlgorithm])
def test_coupled_pendulums_as_model_exchange_give_the_co_simulation_numbers(algorithm):
    """Two pendulums and a torsion spring (a Co-Simulation FMU): with the pendulums integrated
    by the engine the system gives the numbers of their Co-Simulation build (its own CVODE at
    the same tolerance, 1e-11). Both hold the torque over each step and start their integrator
    afresh when it changes, so they differ by the integrators' errors only: 200 steps of a
    local error near the tolerance, 2.2e-9 here."""
    results = {}
    for interface in ("co-simulation", "model-exchange"):
        system = coupled_pendulums.build(algorithm(), interface=interface)
        system.initialize(0.0)
        results[interface] = system.run(0.0, coupled_pendulums.TF, 0.01)
    for name in ("P1", "P2"):
        np.testing.assert_allclose(results["model-exchange"][name][1]["theta"],
                                   results["co-simulation"][name][1]["theta"], rtol=0, atol=1e-8)
    assert results["model-exchange"].statistics.do_step_calls == 600  # 3 components, 200 steps


def test_a_step_after_a_restore_is_the_first_step_bit_for_bit():
    """The engine owns the state: a snapshot holds the FMU state and the continuous states, and
    CVODE starts afresh from them, so stepping again from a restore repeats the steps exactly,
    across a bounce."""
    component = ball(tolerance=1e-8)
    system = one(component)
    engine, sys = lib(), system._plan.sys
    assert engine.ssx_component_snapshot(sys, 0, 0) == 0
    states = []
    for _ in range(2):
        assert engine.ssx_component_do_step(sys, 0, 0.0, 0.3) == 0
        assert engine.ssx_component_do_step(sys, 0, 0.3, 0.3) == 0  # bounces at 0.4515
        states.append(component.instance.getReal([component.value_reference("h"),
                                                  component.value_reference("v")]))
        assert engine.ssx_component_restore(sys, 0, 0, 0.0) == 0
    assert states[0] == states[1]
    assert states[0][1] > 0  # going up: the bounce happened both times


def test_interface_choice_and_its_errors():
    path = fmus.path("bouncing_ball_cvode")
    assert FMUComponent("A", path).model_exchange is False  # auto: Co-Simulation first
    with pytest.raises(ConfigurationError, match=r"component 'C': interface='me' is not one of "
                       r"'auto', 'co-simulation', 'model-exchange'"):
        FMUComponent("C", path, interface="me")
    with pytest.raises(ConfigurationError, match=r"component 'D': isolated=True runs an FMU's "
                       r"Co-Simulation interface only, and bouncing_ball_cvode\.fmu runs as "
                       r"Model Exchange here .* drop isolated=True or pass "
                       r"interface=\"co-simulation\""):
        FMUComponent("D", path, interface="model-exchange", isolated=True)
    component = ball("E")
    one(component)
    with pytest.raises(FMUError, match=r"^E: fmi2DoStep returned failed: the FMU runs as FMI "
                       r"2\.0 Model Exchange, which has no such function$"):
        component.instance.doStep(0.0, 0.1)


def test_the_loader_reads_interface(tmp_path: Path):
    config = tmp_path / "ball.yaml"
    config.write_text("system: {name: ball}\ncomponents:\n  - name: B\n"
                      "    fmu: bouncing_ball_cvode\n    interface: model-exchange\n")
    assert build_system(config).components["B"].model_exchange is True
    config.write_text("system: {name: s}\ncomponents:\n  - name: B\n"
                      "    class: 'quickstart:LinearSource'\n    interface: model-exchange\n")
    with pytest.raises(ConfigurationError, match="'interface' chooses an FMU's interface: it "
                       "needs 'fmu'"):
        build_system(config, allowed_modules=["quickstart"])


def model_exchange_only(tmp_path: Path) -> Path:
    """bouncing_ball_cvode without its CoSimulation element: a Model-Exchange-only FMU."""
    path = tmp_path / "ball_me.fmu"
    with zipfile.ZipFile(fmus.path("bouncing_ball_cvode")) as source, \
            zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as target:
        for item in source.infolist():
            data = source.read(item)
            if item.filename == "modelDescription.xml":
                data = re.sub(rb"  <CoSimulation .*?/>\n", b"", data, flags=re.S)
            target.writestr(item, data)
    return path


def test_a_model_exchange_only_fmu_runs_by_default(tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str]):
    """"auto" takes Model Exchange when the FMU has no Co-Simulation: from Python and from the
    command line without --interface, with the same numbers; asking for Co-Simulation names
    what the FMU has."""
    path = model_exchange_only(tmp_path)
    component = FMUComponent("B", path)
    assert component.model_exchange is True
    t, values = one(component).run(0.0, 1.0, 0.01)["B"]
    # no tolerance given anywhere: the engine's default relative tolerance (FMPy's 1e-5)
    defaults = ffi.new("ssx_defaults *")
    lib().ssx_get_defaults(defaults)
    assert defaults.model_exchange_tolerance == 1e-5
    fall = t < bounce_times()[0]
    assert np.max(np.abs(values["h"][fall] - (1 - G * t[fall] ** 2 / 2))) < 1e-5
    out = tmp_path / "out.csv"
    assert main(["simulate", str(path), "--stop-time", "1", "--step-size", "0.01",
                 "--output", str(out)]) == 0
    heights = np.genfromtxt(out, delimiter=",", names=True)["h"]  # FMPy's CSV: plain names
    np.testing.assert_array_equal(heights, values["h"])
    assert main(["simulate", str(path), "--interface", "co-simulation"]) != 0
    assert "ball_me.fmu has no co-simulation interface (it has model-exchange)" in \
        capsys.readouterr().err
