"""`syssimx run FILE.ssp|FILE.ssd` and `syssimx describe FILE.ssp`, with --algorithm: the
numbers of the same system run in Python."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest
from syssimx import GaussSeidelAlgorithm, JacobiAlgorithm
from syssimx.cli import main
from test_ssp_round_trip import coupled_pendulums


def p2_theta(path: Path) -> np.ndarray:
    with path.open(newline="") as stream:
        return np.array([float(row["value"]) for row in csv.DictReader(stream)
                         if (row["component"], row["port"]) == ("P2", "theta")])


@pytest.mark.parametrize(("option", "algorithm"), [("jacobi", JacobiAlgorithm),
                                                   ("gauss_seidel", GaussSeidelAlgorithm)])
def test_run_an_ssp_with_its_experiment_and_the_algorithm_chosen(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], option: str,
        algorithm: type) -> None:
    path = coupled_pendulums(JacobiAlgorithm()).to_ssp(tmp_path / "p.ssp", 0.0, 0.5, 0.05)
    out = tmp_path / "p.csv"
    assert main(["run", str(path), "--algorithm", option, "--quiet", "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert printed.startswith(f"Completed 'coupled pendulums': t in [0.0, 0.5] s, dt = 0.05 s, "
                              f"algorithm = {algorithm.__name__}, wall time = ")
    system = coupled_pendulums(algorithm())
    system.initialize(0.0)
    expected = system.run(0.0, 0.5, 0.05)["P2"][1]["theta"]
    got = p2_theta(out)
    assert len(got) == 11
    np.testing.assert_allclose(got, expected, rtol=1e-15, atol=0)  # the CSV's %.17g


def test_options_override_the_experiment(tmp_path: Path,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    path = coupled_pendulums(JacobiAlgorithm()).to_ssp(tmp_path / "p.ssp", 0.0, 0.5, 0.05)
    assert main(["run", str(path), "--tf", "0.2", "--dt", "0.1", "--quiet"]) == 0
    assert "t in [0.0, 0.2] s, dt = 0.1 s, algorithm = GaussSeidelAlgorithm" \
        in capsys.readouterr().out


def test_an_ssp_without_stop_time_asks_for_it(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = coupled_pendulums(JacobiAlgorithm()).to_ssp(tmp_path / "p.ssp")
    assert main(["run", str(path), "--quiet"]) == 1
    assert capsys.readouterr().err == (
        f"syssimx: error: {path}: give --stop-time: the file has no stop time\n")


def test_an_ssp_without_step_runs_at_fmpys_output_interval(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """fmpy.util.auto_interval(2.0) = 0.004 (500 round steps), as `simulate` does."""
    path = coupled_pendulums(JacobiAlgorithm()).to_ssp(tmp_path / "p.ssp", 0.0, 2.0)
    assert main(["run", str(path), "--quiet"]) == 0
    assert "t in [0.0, 2.0] s, dt = 0.004 s" in capsys.readouterr().out


def test_describe_an_ssp(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = coupled_pendulums(JacobiAlgorithm()).to_ssp(tmp_path / "p.ssp")
    assert main(["describe", str(path), "--initialize"]) == 0
    text = capsys.readouterr().out
    assert text.startswith("System 'coupled pendulums': 3 components, 6 connections, "
                           "0 event connections\n")
    assert "  Spring.tau2 [N.m] -> P2.torque [N.m]\n" in text


def test_a_bad_ssp_is_one_line_naming_the_file(tmp_path: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "broken.ssd"
    path.write_text("<ssd:SystemStructureDescription")
    assert main(["run", str(path)]) == 1
    err = capsys.readouterr().err
    assert err.startswith(f"syssimx: error: {path}: malformed XML: ")
    assert err.count("\n") == 1


def test_algorithm_for_a_yaml_description(capsys: pytest.CaptureFixture[str]) -> None:
    example = Path(__file__).resolve().parents[2] / "examples" / "coupled_pendulums.yaml"
    assert main(["run", str(example), "--tf", "0.1", "--algorithm", "jacobi", "--quiet"]) == 0
    assert "algorithm = JacobiAlgorithm" in capsys.readouterr().out
