"""The command line under FMPy's flag names with FMPy's meanings (`--relative-tolerance`,
`--output-interval`, `--output-file`, `--start-values`, `--input-file`, `--output-variables`,
`--fmi-type`, `--timeout`), ours as aliases; one set of time and output names across simulate,
run and sweep; a subcommand's own usage on a bad flag; the events `run` located."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.util import read_csv
from syssimx import fmus
from syssimx.cli import build_parser, main

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
# Quarter period of the seed pendulum released at 0.5 rad: ellipk(sin^2(0.25)) / sqrt(mgL/I).
EXACT_WALL_TIME = 0.46507759431173046


def test_fmpys_flags_give_fmpys_result(tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    out = tmp_path / "out.csv"
    assert main(["simulate", "pendulum_euler", "--stop-time", "1.5", "--output-interval", "0.01",
                 "--start-values", "theta0", "1.2", "omega0", "-0.3", "torque", "3",
                 "--relative-tolerance", "1e-6", "--output-variables", "theta", "omega",
                 "--output-file", str(out)]) == 0
    assert capsys.readouterr().out == f"wrote 151 samples of 2 outputs to {out}\n"
    ours = read_csv(out)
    reference = simulate_fmu(fmus.path("pendulum_euler"), stop_time=1.5, output_interval=0.01,
                             relative_tolerance=1e-6,
                             start_values={"theta0": 1.2, "omega0": -0.3, "torque": 3.0},
                             output=["theta", "omega"])
    assert ours.dtype.names == ("time", "theta", "omega")
    for name in ours.dtype.names:
        # the same binary on the same grid: the CSV keeps every digit
        np.testing.assert_allclose(ours[name], reference[name], rtol=0, atol=1e-12)


def test_our_names_are_aliases_of_fmpys(tmp_path: Path):
    fmpy_names, ours = tmp_path / "fmpy.csv", tmp_path / "ours.csv"
    assert main(["simulate", "pendulum_cvode", "--start-time", "0", "--stop-time", "0.5",
                 "--step-size", "0.05", "--relative-tolerance", "1e-8", "--fmi-type",
                 "ModelExchange", "--start-values", "theta0", "0.3",
                 "--output-file", str(fmpy_names)]) == 0
    assert main(["simulate", "pendulum_cvode", "--t0", "0", "--tf", "0.5", "--dt", "0.05",
                 "--tolerance", "1e-8", "--interface", "model-exchange", "--set", "theta0=0.3",
                 "-o", str(ours)]) == 0
    assert fmpy_names.read_text() == ours.read_text()
    co_simulation = tmp_path / "cs.csv"
    assert main(["simulate", "pendulum_cvode", "--stop-time", "0.5", "--step-size", "0.05",
                 "--relative-tolerance", "1e-8", "--fmi-type", "CoSimulation",
                 "--start-values", "theta0", "0.3", "--output-file", str(co_simulation)]) == 0
    assert co_simulation.read_text() != ours.read_text()  # another interface: other digits


def test_output_interval_with_a_step_records_every_fifth_step(tmp_path: Path):
    out = tmp_path / "out.csv"
    assert main(["simulate", "pendulum_euler", "--stop-time", "1", "--step-size", "0.01",
                 "--output-interval", "0.05", "--output-file", str(out)]) == 0
    np.testing.assert_allclose(read_csv(out)["time"], np.linspace(0.0, 1.0, 21), atol=1e-12)


def test_units_are_opt_in(tmp_path: Path):
    out = tmp_path / "out.csv"
    assert main(["simulate", "pendulum_euler", "--stop-time", "0.1", "--units",
                 "--output-file", str(out)]) == 0
    assert out.read_text().splitlines()[0] == "time,theta [rad],omega [rad/s],alpha [rad/s2]"


def test_timeout_writes_the_samples_and_fails(tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str]):
    out = tmp_path / "out.csv"
    assert main(["simulate", "pendulum_euler", "--stop-time", "1e6", "--step-size", "1e-3",
                 "--timeout", "0.3", "--output-file", str(out)]) == 1
    captured = capsys.readouterr()
    assert "--timeout 0.3 s" in captured.err and captured.err.startswith("syssimx: error: ")
    time = read_csv(out)["time"]
    assert 10 < len(time) and time[-1] < 1e6  # what ran before the timeout is kept
    assert f"wrote {len(time)} samples" in captured.out


@pytest.mark.parametrize(("argv", "message"), [
    (["--start-values", "theta0"], "--start-values takes name-value pairs"),
    (["--output-variables", "thetta"], "(did you mean 'theta'?); outputs: theta, omega"),
    (["--fmi-type", "Both"], "expected one of auto, CoSimulation, ModelExchange"),
])
def test_bad_fmpy_flag_values_are_named(argv: list[str], message: str,
                                        capsys: pytest.CaptureFixture[str]):
    assert main(["simulate", "pendulum_euler", *argv]) in (1, 2)
    assert message in capsys.readouterr().err


def test_an_unknown_flag_shows_the_subcommands_usage_and_the_close_flag(
        capsys: pytest.CaptureFixture[str]):
    assert main(["simulate", "pendulum_euler", "--stop-tme", "1"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("usage: syssimx simulate ")
    assert "unrecognized arguments: --stop-tme 1 (did you mean '--stop-time'" in err
    assert main(["run", "x.yaml", "--output-fil", "o.csv", "--t1", "2"]) == 2
    assert capsys.readouterr().err.startswith("usage: syssimx run ")


@pytest.mark.parametrize("command", [["run", "system.yaml"],
                                     ["sweep", "system.yaml", "--param", "P.theta0=0.1,0.2"]])
def test_run_and_sweep_take_the_same_names(command: list[str]):
    fmpy_names = build_parser().parse_args([*command, "--start-time", "1", "--stop-time", "2",
                                       "--step-size", "0.5", "--output-file", "o.csv"])
    ours = build_parser().parse_args([*command, "--t0", "1", "--tf", "2", "--dt", "0.5",
                                 "-o", "o.csv"])
    for name in ("start_time", "stop_time", "step_size", "output"):
        assert getattr(fmpy_names, name) == getattr(ours, name)
    assert (ours.start_time, ours.stop_time, ours.step_size, str(ours.output)) \
        == (1.0, 2.0, 0.5, "o.csv")


def test_run_prints_the_located_events(capsys: pytest.CaptureFixture[str]):
    assert main(["run", str(EXAMPLES / "pendulum_wall.yaml")]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("Completed 'pendulum against a wall'")
    events = re.fullmatch(r"Events: 1 \(at t = (\S+) P\.wall_hit\)", lines[1])
    assert events is not None, lines[1]
    # CVODE at rtol 1e-10 follows the exact solution to ~1e-10; printed to 10 digits
    assert abs(float(events.group(1)) - EXACT_WALL_TIME) < 1e-8


def test_run_lists_the_first_five_of_many_events(capsys: pytest.CaptureFixture[str]):
    assert main(["run", str(EXAMPLES / "pendulum_wall.yaml"), "--stop-time", "6"]) == 0
    line = capsys.readouterr().out.splitlines()[1]
    count = int(re.match(r"Events: (\d+) \(first 5 at ", line).group(1))
    assert count > 5 and line.endswith(", ...)") and line.count("P.wall_hit") == 5


def test_run_takes_the_output_interval_and_keeps_the_event_instants(tmp_path: Path):
    out = tmp_path / "wall.csv"
    assert main(["run", str(EXAMPLES / "pendulum_wall.yaml"), "--output-interval", "0.25",
                 "--output-file", str(out)]) == 0
    rows = [line.split(",") for line in out.read_text().splitlines()[1:]]
    theta = [(float(r[2]), int(r[3])) for r in rows if r[:2] == ["P", "theta"]]
    event = next(t for t, micro in theta if micro == 1)
    assert abs(event - EXACT_WALL_TIME) < 1e-8
    assert theta == [(0.0, 0), (0.25, 0), (event, 0), (event, 1), (0.5, 0), (0.75, 0), (1.0, 0)]


def test_run_timeout_writes_the_samples_and_fails(tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]):
    out = tmp_path / "long.csv"
    assert main(["run", str(EXAMPLES / "pendulum_wall.yaml"), "--stop-time", "1e5",
                 "--step-size", "1e-4", "--timeout", "0.3", "--output-file", str(out)]) == 1
    err = capsys.readouterr().err
    assert "exceeded timeout=0.3 s" in err and f"written to {out}" in err
    assert len(out.read_text().splitlines()) > 10
