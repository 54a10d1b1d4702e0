"""The examples run and print what they promise."""

from __future__ import annotations

import runpy
from itertools import pairwise
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def run_example(name: str, capsys: pytest.CaptureFixture[str]) -> str:
    runpy.run_path(str(EXAMPLES / f"{name}.py"), run_name="__main__")
    return capsys.readouterr().out


def test_quickstart_prints_12_25(capsys: pytest.CaptureFixture[str]):
    assert run_example("quickstart", capsys).split() == ["5.0", "12.25"]


def test_bouncing_ball_stops_at_zeno_with_matching_bounces(capsys: pytest.CaptureFixture[str]):
    out = run_example("bouncing_ball", capsys)
    assert "chattering" in out
    assert "41 bounces" in out
    differences = [float(line.split()[-1]) for line in out.splitlines()[-10:]]
    assert max(abs(d) for d in differences) < 1e-8


def test_coupled_pendulums_error_halves_with_dt(capsys: pytest.CaptureFixture[str]):
    rows = [line.split() for line in run_example("coupled_pendulums", capsys).splitlines()[1:]]
    for algorithm in ("Jacobi", "Gauss-Seidel"):
        errors = [float(r[-1]) for r in rows if r[0] == algorithm]
        assert len(errors) == 3
        assert all(1.6 < a / b < 2.4 for a, b in pairwise(errors))
