"""A Model Exchange FMU in a System: coupled to Co-Simulation FMUs under Jacobi and
Gauss-Seidel, under an external event indicator the master locates by rollback while the FMU's
own events are handled inside its steps, rolled back exactly, and chosen by `interface=` from
Python, the command line and the YAML loader.

The Model Exchange FMUs are the Reference FMUs (Dahlquist: x' = -x; BouncingBall; Feedthrough),
found as in test_reference_fmus.py.
"""

from __future__ import annotations

import re
import zipfile
from pathlib import Path

import numpy as np
import pytest
from syssimx import (
    ConfigurationError,
    Connection,
    FMUComponent,
    FMUError,
    GaussSeidelAlgorithm,
    JacobiAlgorithm,
    System,
    fmus,
)
from syssimx.cli import main
from syssimx.engine import ffi, lib
from syssimx.system.loader import build_system
from test_model_exchange_reference import G, bounce_times, fmu
from test_reference_fmus import read_result

DT = 0.1


def dahlquist_chain(algorithm) -> tuple[System, dict[str, np.ndarray]]:
    """Dahlquist (ME) -> gain (CS, k = 3) -> Feedthrough (ME): a Model Exchange output drives a
    Co-Simulation input, whose output drives a Model Exchange input."""
    system = System("chain")
    system.add_component(FMUComponent("D", fmu("Dahlquist"), interface="model-exchange",
                                      tolerance=1e-10))
    gain = FMUComponent("K", fmus.path("gain"))
    gain.set_parameters(k=3.0)
    system.add_component(gain)
    system.add_component(FMUComponent("F", fmu("Feedthrough"), interface="model-exchange"))
    system.add_connection(Connection("D", "x", "K", "u"))
    system.add_connection(Connection("K", "y", "F", "Float64_continuous_input"))
    system.set_algorithm(algorithm)
    system.initialize(0.0)
    result = system.run(0.0, 1.0, DT)
    t = result["D"][0]
    return system, {"t": t, "x": result["D"][1]["x"], "y": result["K"][1]["y"],
                    "out": result["F"][1]["Float64_continuous_output"]}


def test_jacobi_holds_each_model_exchange_input_over_the_step():
    """Jacobi: every input comes from the outputs at the step's start, so the gain lags the
    integrated state by one step and the Feedthrough by two."""
    _, v = dahlquist_chain(JacobiAlgorithm())
    np.testing.assert_allclose(v["x"], np.exp(-v["t"]), rtol=0, atol=1e-9)
    np.testing.assert_array_equal(v["y"][1:], 3.0 * v["x"][:-1])
    np.testing.assert_array_equal(v["out"][1:], v["y"][:-1])


def test_gauss_seidel_passes_model_exchange_outputs_on_within_the_step():
    """Gauss-Seidel: the gain's output feeds a direct-feedthrough path, so the gain steps after
    the Dahlquist FMU and reads the state it just reached; the Feedthrough's output goes
    nowhere, so it steps first (a consumer before its delayed producer) and lags one step."""
    _, v = dahlquist_chain(GaussSeidelAlgorithm())
    np.testing.assert_allclose(v["x"], np.exp(-v["t"]), rtol=0, atol=1e-9)
    np.testing.assert_array_equal(v["y"], 3.0 * v["x"])
    np.testing.assert_array_equal(v["out"][1:], v["y"][:-1])


def fall_crossings(level: float) -> list[float]:
    """When the closed-form ball falls through `level` (before it rests)."""
    times, bounces = [], bounce_times()
    start, speed = 0.0, 0.0  # flight start (a bounce), upward speed there
    height = 1.0
    for land in bounces:
        # h(s) = height + speed s - G s^2 / 2 reaches level on the way down
        if height + speed**2 / (2 * G) > level:
            times.append(start + (speed + np.sqrt(speed**2 + 2 * G * (height - level))) / G)
        speed, start, height = G * (land - start) * 0.7 - 0.7 * speed, land, 0.0
    return times


def test_external_indicator_is_located_by_rollback_and_own_events_recorded_once():
    """An indicator of the master on the ball's height (h = 0.2, falling) is located by
    restoring and re-stepping the ME component; the ball's bounces, its own state events, are
    handled inside its steps and recorded once each, however often localization repeats the
    steps they lie in."""
    ball = FMUComponent("B", fmu("BouncingBall"), interface="model-exchange", tolerance=1e-12)
    ball.add_event_indicator("low", lambda b: b.get_outputs()["h"].magnitude - 0.2,
                             direction=-1)
    system = System("ball")
    system.add_component(ball)
    system.initialize(0.0)
    system.algorithm.tol_time = 1e-10
    result = system.run(0.0, 3.0, 0.01)
    own = [e for e in result.events if e.own]
    master = [e for e in result.events if not e.own]
    assert [e.event for e in own] == ["state_event"] * 11
    assert np.max(np.abs(np.array([e.t for e in own]) - bounce_times())) < 1e-8
    assert result.statistics.own_events == 11
    assert result.statistics.state_restores > 0
    assert len(master) == len(fall_crossings(0.2))
    assert np.max(np.abs(np.array([e.t for e in master]) - fall_crossings(0.2))) < 1e-9


def test_a_step_after_a_restore_is_the_first_step_bit_for_bit():
    """The engine owns the state: a snapshot holds the FMU state and the continuous states, and
    CVODE starts afresh from them, so stepping again from a restore repeats the step exactly
    (across a bounce, the ball's event included)."""
    ball = FMUComponent("B", fmu("BouncingBall"), interface="model-exchange", tolerance=1e-8)
    system = System("ball")
    system.add_component(ball)
    system.initialize(0.0)
    plan = system._plan
    engine = lib()
    assert engine.ssx_component_snapshot(plan.sys, 0, 0) == 0
    steps = []
    for _ in range(2):
        assert engine.ssx_component_do_step(plan.sys, 0, 0.0, 0.3) == 0
        assert engine.ssx_component_do_step(plan.sys, 0, 0.3, 0.3) == 0  # bounces at 0.45
        steps.append(ball.instance.getReal([ball.value_reference("h"),
                                            ball.value_reference("v")]))
        assert engine.ssx_component_restore(plan.sys, 0, 0, 0.0) == 0
    assert steps[0] == steps[1]
    assert steps[0][1] > 0  # going up again: the bounce happened in both


def test_interface_choice_and_its_errors(tmp_path: Path):
    ball = fmu("BouncingBall")
    assert FMUComponent("A", ball).model_exchange is False  # auto: Co-Simulation first
    assert FMUComponent("B", ball, interface="model-exchange").model_exchange is True
    with pytest.raises(ConfigurationError, match=r"component 'C': interface='me' is not one of "
                       r"'auto', 'co-simulation', 'model-exchange'"):
        FMUComponent("C", ball, interface="me")
    model_exchange = FMUComponent("E", ball, interface="model-exchange")
    system = System("one")
    system.add_component(model_exchange)
    system.initialize(0.0)
    with pytest.raises(FMUError, match=r"^E: fmi2DoStep returned failed: the FMU runs as FMI 2\.0 "
                       r"Model Exchange, which has no such function$"):
        model_exchange.instance.doStep(0.0, 0.1)
    with pytest.raises(ConfigurationError, match=r"component 'D': isolated=True runs an FMU's "
                       r"Co-Simulation interface only, and BouncingBall\.fmu runs as Model "
                       r"Exchange here .* drop isolated=True or pass "
                       r"interface=\"co-simulation\""):
        FMUComponent("D", ball, interface="model-exchange", isolated=True)


def test_the_loader_reads_interface(tmp_path: Path):
    config = tmp_path / "ball.yaml"
    config.write_text(f"system: {{name: ball}}\ncomponents:\n  - name: B\n"
                      f"    fmu: {fmu('BouncingBall')}\n    interface: model-exchange\n")
    system = build_system(config)
    assert system.components["B"].model_exchange is True
    config.write_text("system: {name: s}\ncomponents:\n  - name: B\n"
                      "    class: 'quickstart:LinearSource'\n    interface: model-exchange\n")
    with pytest.raises(ConfigurationError, match="'interface' chooses an FMU's interface: it "
                       "needs 'fmu'"):
        build_system(config)


def model_exchange_only(tmp_path: Path) -> Path:
    """The Reference BouncingBall without its CoSimulation element: a Model-Exchange-only FMU."""
    path = tmp_path / "BouncingBallME.fmu"
    with zipfile.ZipFile(fmu("BouncingBall")) as source, \
            zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as target:
        for item in source.infolist():
            data = source.read(item)
            if item.filename == "modelDescription.xml":
                data = re.sub(rb"<CoSimulation.*?</CoSimulation>", b"", data, flags=re.S)
            target.writestr(item, data)
    return path


def test_a_model_exchange_only_fmu_runs_by_default(tmp_path: Path):
    """"auto" takes Model Exchange when the FMU has no Co-Simulation: from Python and from the
    command line without --interface, with the same numbers; asking for Co-Simulation fails."""
    path = model_exchange_only(tmp_path)
    ball = FMUComponent("B", path)
    assert ball.model_exchange is True
    system = System("ball")
    system.add_component(ball)
    system.initialize(0.0)
    t, values = system.run(0.0, 1.0, 0.01)["B"]
    # no tolerance given anywhere: the engine's default relative tolerance (FMPy's 1e-5)
    defaults = ffi.new("ssx_defaults *")
    lib().ssx_get_defaults(defaults)
    assert defaults.model_exchange_tolerance == 1e-5
    fall = t < bounce_times()[0]
    assert np.max(np.abs(values["h"][fall] - (1 - G * t[fall] ** 2 / 2))) < 1e-5
    out = tmp_path / "out.csv"
    assert main(["simulate", str(path), "--stop-time", "1", "--step-size", "0.01",
                 "--output", str(out)]) == 0
    np.testing.assert_array_equal(read_result(out)["h"], values["h"])
    assert main(["simulate", str(path), "--interface", "co-simulation"]) != 0
