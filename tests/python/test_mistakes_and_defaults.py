"""Mistakes a user makes are SysSimXError subclasses (also the builtin a Python user expects)
with "did you mean ...?" for close names; the defaults FMPy and SysSimX users expect for a step
that does not fit the run and for parameters set after initialize; the package's own words."""

from __future__ import annotations

import os
import subprocess
import sys
import tomllib
import warnings
from pathlib import Path

import numpy as np
import pytest
import syssimx
from syssimx import (
    ConfigurationError,
    Connection,
    FMUComponent,
    SysSimXError,
    System,
    fmus,
)
from syssimx.errors import SysSimXWarning

ROOT = Path(__file__).resolve().parents[2]


def pendulum_system() -> System:
    system = System("one")
    system.add_component(FMUComponent("P", fmus.path("pendulum_euler")))
    return system


def test_a_wrong_value_type_is_a_syssimx_error_and_a_type_error():
    component = FMUComponent("G", fmus.path("gain"))
    spec = component.input_specs["u"]
    with pytest.raises(SysSimXError) as raised:
        spec.coerce("three")
    assert isinstance(raised.value, TypeError) and isinstance(raised.value, ConfigurationError)
    assert str(raised.value) == "port 'u' is REAL; got str"


def test_a_misspelled_bundled_fmu_suggests_the_name():
    with pytest.raises(SysSimXError) as raised:
        fmus.path("pendulum_cvod")
    assert isinstance(raised.value, FileNotFoundError)
    message = str(raised.value)
    assert message.startswith("no bundled FMU named 'pendulum_cvod' (did you mean "
                              "'pendulum_cvode'")
    assert len(message) < 200  # the close names, not the whole list


@pytest.mark.parametrize(("mistake", "suggestion"), [
    (lambda s: s.components["P"].set_parameters(theta_0=0.1), "(did you mean 'theta0'?)"),
    (lambda s: s.components["P"].set_inputs({"torqe": 1.0}), "(did you mean 'torque'?)"),
    (lambda s: s.add_connection(Connection("P", "thetta", "P", "torque")),
     "(did you mean 'theta'?)"),
    (lambda s: s.add_connection(Connection("p", "theta", "P", "torque")),
     "unknown component 'p' (did you mean 'P'?)"),
])
def test_close_names_are_suggested(mistake, suggestion: str):
    with pytest.raises(ConfigurationError, match=suggestion.replace("(", r"\(")
                       .replace(")", r"\)").replace("?", r"\?")):
        mistake(pendulum_system())


def test_a_cli_set_name_is_suggested(capsys: pytest.CaptureFixture[str]):
    from syssimx.cli import main

    assert main(["simulate", "pendulum_euler", "--set", "thta0=1"]) == 1
    assert "has no parameter 'thta0' (did you mean 'theta0'?)" in capsys.readouterr().err


def test_a_plot_of_a_misspelled_signal_suggests_the_port():
    system = pendulum_system()
    system.initialize(0.0)
    result = system.run(0.0, 0.1, 0.05)
    with pytest.raises(ConfigurationError, match=r"has no port 'omeg' \(did you mean 'omega'"):
        result.plot(["P.omeg"])


def test_a_step_longer_than_the_run_is_refused():
    system = pendulum_system()
    system.initialize(0.0)
    with pytest.raises(ConfigurationError, match=r"dt=1\.0 is longer than the run from "
                                                  r"t0=0\.0 to tf=0\.01"):
        system.run(0.0, 0.01, 1.0)  # tf and dt swapped


def test_a_step_that_does_not_divide_the_run_warns_and_ends_at_tf():
    system = pendulum_system()
    system.initialize(0.0)
    with pytest.warns(SysSimXWarning, match=r"dt=0\.3 does not divide tf - t0 = 1\.0: the last "
                                            r"step is 0\.1 s"):
        result = system.run(0.0, 1.0, 0.3)
    np.testing.assert_allclose(result["P"][0], [0.0, 0.3, 0.6, 0.9, 1.0], rtol=0, atol=1e-12)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        system.run(1.0, 2.0, 0.25)  # one that divides: no warning


def test_set_parameters_after_initialize_applies_at_the_next_initialize():
    system = pendulum_system()
    system.initialize(0.0)
    first = system.run(0.0, 0.1, 0.05)["P"][1]["theta"][0]
    system.components["P"].set_parameters(theta0=0.25)
    with pytest.warns(SysSimXWarning, match=r"P.set_parameters\(theta0\) after initialize: the "
                                            r"running FMU keeps its values"):
        later = system.run(0.1, 0.2, 0.05)
    assert later["P"][1]["theta"][0] == first  # the run goes on unchanged
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # said once; and set before initialize, it is no mistake
        system.run(0.2, 0.3, 0.05)
        system.components["P"].set_parameters(theta0=0.25)
        system.initialize(0.0)
        assert system.run(0.0, 0.1, 0.05)["P"][1]["theta"][0] == 0.25


def test_the_seed_s_handler_sets_parameters_in_initialization_mode_without_a_warning():
    import hybrid_pendulum  # examples/: the seed tutorial's own subclass

    for solver in ("euler", "cvode"):  # the two handlers: a new instance, a restored state
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            _, _, event_time = hybrid_pendulum.simulate(solver)
        # Euler: its own discretization error of 2e-6 (test_hybrid_pendulum.py holds the figures)
        assert event_time == pytest.approx(0.46507759431173046, abs=1e-5)


def test_no_stale_fmi_2_0_co_simulation_only_words():
    assert "FMI 1.0, 2.0 and 3.0" in syssimx.__doc__
    description = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["description"]
    assert "3.0" in description and "Model Exchange" in description
    environment = dict(os.environ)
    if environment.get("SYSSIMX_BUILD_DIR"):  # the command runs in another folder
        environment["SYSSIMX_BUILD_DIR"] = str(Path(environment["SYSSIMX_BUILD_DIR"]).resolve())
    help_text = subprocess.run([sys.executable, "-m", "syssimx.cli", "--help"],
                               capture_output=True, text=True, check=True, env=environment,
                               cwd=Path(syssimx.__file__).parents[1]).stdout
    assert "FMI 1.0, 2.0 and 3.0, Co-Simulation and Model Exchange" \
        in " ".join(help_text.split())


def test_a_result_names_what_it_does_not_hold_as_a_key_error():
    system = pendulum_system()
    system.initialize(0.0)
    result = system.run(0.0, 0.1, 0.05)
    with pytest.raises(KeyError) as raised:
        result["p"]
    assert isinstance(raised.value, SysSimXError)
    assert str(raised.value) == "no component 'p' (did you mean 'P'?); components: ['P']"
    with pytest.raises(SysSimXError, match=r"recorded no port 'thetta' \(did you mean 'theta'"):
        system.history.save_csv("unused.csv", port_names={"P": ["thetta"]})
