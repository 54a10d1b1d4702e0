"""`syssimx simulate`: one FMU as a one-component system, checked against FMPy and the exact
pendulum."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.util import read_csv as fmpy_read_csv
from matplotlib.image import imread
from syssimx import fmus
from syssimx.cli import main

# Quarter period of the seed pendulum released at 0.5 rad: ellipk(sin^2(0.25)) / sqrt(mgL/I).
EXACT_WALL_TIME = 0.46507759431173046


def test_csv_equals_fmpy_on_the_same_grid(tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    csv_path, png_path = tmp_path / "out.csv", tmp_path / "out.png"
    argv = ["simulate", "pendulum_euler", "--stop-time", "1.5", "--step-size", "0.01",
            "--set", "theta0=1.2", "--set", "omega0=-0.3", "--set", "torque=3",
            "--output", str(csv_path),
            "--plot", str(png_path)]
    assert main(argv) == 0
    assert capsys.readouterr().out.splitlines() == [
        f"wrote 151 samples of 3 outputs to {csv_path}",
        f"wrote the plot to {png_path}",
    ]
    # FMPy's CSV: plain names, time first; FMPy's own reader reads it
    assert csv_path.read_text().splitlines()[0] == "time,theta,omega,alpha"
    ours = fmpy_read_csv(csv_path)
    reference = simulate_fmu(fmus.path("pendulum_euler"), start_time=0.0, stop_time=1.5,
                             output_interval=0.01,
                             start_values={"theta0": 1.2, "omega0": -0.3, "torque": 3.0},
                             output=["theta", "omega", "alpha"])
    assert ours.dtype.names == ("time", "theta", "omega", "alpha")
    for column in ours.dtype.names:
        # The same binary stepped on the same grid; the CSV keeps all 17 digits.
        np.testing.assert_allclose(ours[column], reference[column], rtol=0, atol=1e-12)
    assert imread(png_path).shape[2] in (3, 4)


def test_event_is_located_at_the_exact_quarter_period(capsys: pytest.CaptureFixture[str]):
    argv = ["simulate", "pendulum_cvode", "--stop-time", "1", "--step-size", "0.05",
            "--set", "theta0=0.5", "--set", "cvode_relative_tolerance=1e-10",
            "--event", "theta:falling"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    times = [float(t) for t in re.findall(r"event Pendulum\.theta_crossing at t = (\S+)", out)]
    assert len(times) == 1
    # CVODE at rtol 1e-10 follows the exact solution to ~1e-10; the bracket ends within 1e-9.
    assert abs(times[0] - EXACT_WALL_TIME) < 1e-8
    # Without --output the final values are printed; theta after the swing through zero.
    final_theta = re.search(r"^theta = (\S+) at t = 1$", out, re.MULTILINE)
    assert final_theta is not None and float(final_theta.group(1)) < 0


def test_csv_of_a_run_with_an_event_repeats_the_event_time(tmp_path: Path,
                                                          capsys: pytest.CaptureFixture[str]):
    """The wide layout of result.to_csv: no micro column, the event instant is two rows (before
    and after handling), as in SysSimX's CSV."""
    out = tmp_path / "out.csv"
    argv = ["simulate", "pendulum_cvode", "--stop-time", "1", "--step-size", "0.05",
            "--set", "theta0=0.5", "--set", "cvode_relative_tolerance=1e-10",
            "--event", "theta:falling", "--output", str(out)]
    assert main(argv) == 0
    event_time = float(re.search(r"at t = (\S+)", capsys.readouterr().out).group(1))
    assert out.read_text().splitlines()[0] == "time,theta,omega,alpha"
    times = fmpy_read_csv(out)["time"]
    assert len(times) == 21 + 2
    assert times.tolist().count(event_time) == 2


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--set", "bogus=1"], "component 'Pendulum' has no parameter 'bogus'"),
        (["--event", "torque:1"], "--event torque: not an output of pendulum_cvode.fmu"),
        (["--step-size", "-1"], "step size > 0"),
        (["--start-time", "2", "--stop-time", "1"], "stop time > start time"),
    ],
)
def test_bad_simulation_input_exits_1(argv: list[str], message: str,
                                      capsys: pytest.CaptureFixture[str]):
    assert main(["simulate", "pendulum_cvode", *argv]) == 1
    captured = capsys.readouterr()
    assert captured.err.startswith("syssimx: error: ") and message in captured.err
    assert "Traceback" not in captured.err and captured.out == ""
