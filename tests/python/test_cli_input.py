"""`syssimx simulate FMU --input FILE.csv`: the columns drive the inputs of the same name, with
FMPy's numbers."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.util import read_csv
from syssimx import fmus
from syssimx.cli import main

# torque with a jump at 0.4 s (a repeated time stamp); "brake" names no input of the pendulum
SIGNALS = "time,torque,brake\n0,0,1\n0.4,2,1\n0.4,-1,0\n1,3,0\n"


def read_columns(path: Path) -> dict[str, np.ndarray]:
    """The columns by port name (the header is "time", then "port [unit]")."""
    with path.open(newline="") as stream:
        rows = list(csv.reader(stream))
    names = (name.split(" [")[0] for name in rows[0])
    return dict(zip(names, np.array(rows[1:], dtype=float).T, strict=True))


def test_input_columns_drive_the_inputs_as_in_fmpy(tmp_path: Path,
                                                    capsys: pytest.CaptureFixture[str]):
    signals, out = tmp_path / "signals.csv", tmp_path / "out.csv"
    signals.write_text(SIGNALS)
    argv = ["simulate", "pendulum_euler", "--input", str(signals), "--stop-time", "1.5",
            "--step-size", "0.01", "--output", str(out)]
    assert main(argv) == 0
    captured = capsys.readouterr()
    assert captured.err == (f"syssimx: warning: {signals}: brake names no input of Pendulum; "
                            "ignored\n")
    ours = read_columns(out)
    theirs = simulate_fmu(fmus.path("pendulum_euler"), stop_time=1.5, output_interval=0.01,
                          input=read_csv(signals), output=["theta", "omega", "alpha"])
    assert list(ours) == ["time", "theta", "omega", "alpha"]
    for column in ours:
        # the same binary, grid and inputs: equal to rounding
        np.testing.assert_allclose(ours[column], theirs[column], rtol=1e-12, atol=1e-15)
    # alpha = (torque - m g L sin(theta)) / I: the torque arrived, its jump at 0.4 s (applied
    # from the step starting there) turns the acceleration around
    assert ours["alpha"][40] > 0 > ours["alpha"][41]


@pytest.mark.parametrize(("content", "reason"), [
    ("time,torque\n0,1\n1,zero\n", "could not convert string to float: 'zero'"),
    ("time,torque\n", "list index out of range"),
])
def test_a_broken_input_file_is_named(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                      content: str, reason: str):
    signals = tmp_path / "signals.csv"
    signals.write_text(content)
    assert main(["simulate", "pendulum_euler", "--input", str(signals)]) == 1
    assert capsys.readouterr().err == (
        f"syssimx: error: --input: {signals} is not a table in FMPy's CSV format (a header "
        f"line, then one line of numbers per time): {reason}\n")


def test_a_missing_input_file_is_named(tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    missing = tmp_path / "missing.csv"
    assert main(["simulate", "pendulum_euler", "--input", str(missing)]) == 1
    assert capsys.readouterr().err == f"syssimx: error: --input: no CSV file {str(missing)!r}\n"


def test_times_going_back_are_named(tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    signals = tmp_path / "signals.csv"
    signals.write_text("time,torque\n0,1\n2,2\n1,3\n")
    assert main(["simulate", "pendulum_euler", "--input", str(signals)]) == 1
    assert capsys.readouterr().err == (
        "syssimx: error: signals.csv: table 'signals.csv': the time goes back from 2 to 1 in "
        "row 2; times must not decrease\n")


def test_a_jump_between_grid_points_is_a_communication_point_as_in_fmpy(tmp_path: Path):
    """The pendulum can vary its step, so FMPy steps to the jump at 0.405 and on to 0.41; so
    does syssimx, and the results agree (one sample more than the grid)."""
    signals, out = tmp_path / "signals.csv", tmp_path / "out.csv"
    signals.write_text("time,torque\n0,0\n0.405,2\n0.405,-1\n1,3\n")
    argv = ["simulate", "pendulum_euler", "--input", str(signals), "--stop-time", "1.5",
            "--step-size", "0.01", "--output", str(out)]
    assert main(argv) == 0
    ours = read_columns(out)
    theirs = simulate_fmu(fmus.path("pendulum_euler"), stop_time=1.5, output_interval=0.01,
                          input=read_csv(signals), output=["theta", "omega", "alpha"])
    assert len(ours["time"]) == len(theirs) == 152
    assert ours["time"][40:43].tolist() == pytest.approx([0.4, 0.405, 0.41], rel=1e-15)
    for column in ours:
        # the grid after the jump is computed from its segment's start: times agree to 1e-15
        np.testing.assert_allclose(ours[column], theirs[column], rtol=1e-12, atol=1e-15)
