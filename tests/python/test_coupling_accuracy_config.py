"""Input order and step control reached from a YAML description and from `syssimx run`."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest
from syssimx.cli import build_parser, main
from syssimx.system import ConfigError, build_system, load_config, run_from_config

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def description(algorithm: dict) -> dict:
    config = load_config(EXAMPLES / "coupled_pendulums.yaml")
    config["algorithm"] = algorithm
    config["run"] = {"t0": 0.0, "tf": 0.5, "dt": 0.1}
    return config


def test_yaml_reaches_input_order_and_step_control():
    result = run_from_config(description({
        "type": "gauss_seidel", "input_order": 2,
        "step_control": {"rtol": 1e-5, "atol": 1e-5, "rollback": False}}))
    stats = result.statistics
    assert stats.accepted_steps == stats.macro_steps > 5  # more steps than the grid's 5
    assert stats.rejected_steps == 0
    assert len(result["P1"][0]) == 6  # samples on the grid only


def test_yaml_hybrid_coupling_takes_a_step_control():
    system = build_system(description({
        "type": "hybrid", "coupling": {"type": "jacobi", "step_control": {}}}))
    assert system.algorithm.coupling.step_control is not None


def test_yaml_reaches_the_energy_step_control():
    result = run_from_config(description({
        "type": "jacobi", "step_control": {
            "error": "energy", "rollback": False, "rtol": 1e-3, "atol": 1e-3,
            "power_bonds": [[["P1", "torque"], ["Spring", "omega1"]],
                            [["P2", "torque"], ["Spring", "omega2"]]]}}))
    assert result.statistics.accepted_steps > 5


def test_yaml_reaches_extrapolated_held_inputs():
    system = build_system(description({
        "type": "jacobi", "input_order": 1, "extrapolate_held_inputs": True}))
    assert system.algorithm.extrapolate_held_inputs is True
    assert build_system(description({"type": "jacobi"})).algorithm.extrapolate_held_inputs \
        is False  # the default: held at the step's start


@pytest.mark.parametrize(("options", "named"), [
    ({"input_order": 3}, "input order is 0, 1 or 2"),
    ({"extrapolate_held_inputs": "yes"}, "extrapolate_held_inputs must be true or false"),
    ({"step_control": {"min_change": 1.5}}, "0 < min_change < 1 < max_change"),
    ({"step_control": {"error": "energy", "power_bonds": [[["P1", "torque"],
                                                           ["Spring", "omega1"]]],
                       "integral_gain": 0.0}}, "integral_gain > 0"),
    ({"step_control": {"error": "power"}}, "error must be 'coupling' or 'energy'"),
    ({"step_control": {"power_bonds": [["P1", "torque"]]}}, "each bond is two"),
    ({"step_control": {"power_bonds": "P1.torque"}}, "power_bonds must be a list of bonds"),
    ({"step_control": {"rtol": -1.0}}, "rtol >= 0"),
    ({"step_control": {"tolerance": 1e-3}}, "tolerance"),
])
def test_yaml_refuses_bad_options_naming_them(options, named):
    with pytest.raises(ConfigError, match=named):
        build_system(description({"type": "jacobi", **options}))


def test_cli_flags_choose_input_order_and_step_tolerance(tmp_path: Path, capsys):
    output = tmp_path / "out.csv"
    assert main(["run", str(EXAMPLES / "coupled_pendulums.yaml"), "--tf", "0.5",
                 "--input-order", "1", "--step-tolerance", "1e-4", "-o", str(output)]) == 0
    assert "Completed 'coupled pendulums'" in capsys.readouterr().out
    with output.open() as f:
        rows = list(csv.DictReader(f))
    # the description's grid (dt 0.01) is the output grid: 51 samples per port
    assert len({row["time"] for row in rows}) == 51


def test_cli_flag_extrapolates_held_inputs(tmp_path: Path, capsys):
    output = tmp_path / "out.csv"
    args = build_parser().parse_args(["run", "system.yaml", "--input-order", "2",
                                      "--extrapolate-held-inputs"])
    assert args.extrapolate_held_inputs is True and args.input_order == 2
    assert build_parser().parse_args(["run", "system.yaml"]).extrapolate_held_inputs is None
    assert main(["run", str(EXAMPLES / "coupled_pendulums.yaml"), "--tf", "0.5",
                 "--input-order", "1", "--extrapolate-held-inputs", "-o", str(output)]) == 0
    assert "Completed 'coupled pendulums'" in capsys.readouterr().out
