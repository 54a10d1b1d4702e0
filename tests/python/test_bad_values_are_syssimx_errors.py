"""Bad values of a step control, from Python, YAML or an OSP <EccoConfiguration>, are
SysSimXErrors naming the option and where it came from (before: bare ValueErrors, and YAML's
`rollback: maybe` was taken as rollback on)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest
from ecco_structure import Ecco, write_structure
from syssimx import JacobiAlgorithm, StepControl
from syssimx.errors import ConfigurationError, SysSimXError
from syssimx.osp import OSPError, read
from syssimx.system import ConfigError, build_system, load_config

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize(("options", "named"), [
    ({"rollback": "maybe"}, "step_control.rollback must be true or false, got 'maybe'"),
    ({"rollback": 1}, "step_control.rollback must be true or false, got 1"),
    ({"error": "power"}, "step_control.error must be 'coupling' or 'energy'"),
    ({"rtol": "tight"}, "step_control.rtol must be a number, got 'tight'"),
    ({"safety": -1.0}, "0 < safety <= 1; got"),
])
def test_a_bad_step_control_is_a_configuration_error(options: dict, named: str):
    with pytest.raises(ConfigurationError) as caught:
        JacobiAlgorithm(step_control=StepControl(**options)).validate()
    assert named in str(caught.value)


def test_yaml_rollback_maybe_is_refused():
    config = load_config(EXAMPLES / "coupled_pendulums.yaml")
    config["algorithm"] = {"type": "jacobi", "step_control": {"rollback": "maybe"}}
    with pytest.raises(ConfigError) as caught:
        build_system(config)
    assert "step_control.rollback must be true or false, got 'maybe'" in str(caught.value)


@pytest.mark.parametrize(("change", "named"), [
    ({"safety": -1.0}, "0 < safety"),
    ({"min_change": 2.0}, "min_change"),
    ({"i_gain": 0.0}, "integral_gain > 0"),
    ({"min_step": 1.0, "max_step": 0.1}, "min_step"),
])
def test_bad_ecco_values_are_osp_errors_naming_the_file(tmp_path: Path, change: dict,
                                                        named: str):
    path = write_structure(tmp_path, replace(Ecco(tolerance=1e-4), **change))
    with pytest.raises(OSPError) as caught:
        read(path)
    message = str(caught.value)
    assert isinstance(caught.value, SysSimXError)
    assert message.startswith(f"{path}: <EccoConfiguration>: ")
    assert named in message
