"""`syssimx simulate` takes start, stop, step and tolerance as FMPy's simulate_fmu does, and
`syssimx --version`; every failure prints a message."""

from __future__ import annotations

import csv
import re
import zipfile
from pathlib import Path

import numpy as np
import pytest
from fmpy import simulate_fmu
from syssimx import FMUComponent, __version__, fmus
from syssimx.cli import main


def read_columns(path: Path) -> dict[str, np.ndarray]:
    """The columns by port name (the header is "time", then "port [unit]")."""
    with path.open(newline="") as stream:
        rows = list(csv.reader(stream))
    names = (name.split(" [")[0] for name in rows[0])
    return dict(zip(names, np.array(rows[1:], dtype=float).T, strict=True))


def simulate(tmp_path: Path, fmu: str, *options: str) -> dict[str, np.ndarray]:
    out = tmp_path / "out.csv"
    assert main(["simulate", fmu, "--output", str(out), *options]) == 0
    return read_columns(out)


def with_experiment(tmp_path: Path, experiment: str) -> str:
    """The bundled pendulum_euler with its DefaultExperiment element replaced."""
    source = fmus.path("pendulum_euler")
    target = tmp_path / "pendulum_variant.fmu"
    with zipfile.ZipFile(source) as original, zipfile.ZipFile(target, "w") as variant:
        for item in original.infolist():
            data = original.read(item.filename)
            if item.filename == "modelDescription.xml":
                data = re.sub(rb"<DefaultExperiment[^>]*/>", experiment.encode(), data)
            variant.writestr(item, data)
    return str(target)


def assert_equals_fmpy(ours: dict[str, np.ndarray], fmu: str, **fmpy_options: float) -> None:
    theirs = simulate_fmu(fmu, output=["theta", "omega", "alpha"], **fmpy_options)
    assert len(ours["time"]) == len(theirs)
    for column in ("time", "theta", "omega", "alpha"):
        # the same binary on the same grid: equal to rounding
        np.testing.assert_allclose(ours[column], theirs[column], rtol=1e-12, atol=1e-14)


def test_the_default_experiment_gives_start_stop_and_step(tmp_path: Path):
    """pendulum_euler declares 0 to 3 s in steps of 1e-3: FMPy doubles the step while there
    are over 1000 steps, to 4e-3 (751 samples)."""
    ours = simulate(tmp_path, fmus.path("pendulum_euler"))
    assert len(ours["time"]) == 751
    assert ours["time"][1] == 0.004 and ours["time"][-1] == 3.0
    assert_equals_fmpy(ours, fmus.path("pendulum_euler"))


@pytest.mark.parametrize(("experiment", "samples", "stop"), [
    ('<DefaultExperiment startTime="0.5" stopTime="3.5"/>', 601, 3.5),  # 5e-3 for 3 s
    ("", 501, 1.0),  # no experiment: 0 to 1 s, 2e-3
    ('<DefaultExperiment stopTime="20"/>', 501, 20.0),  # 4e-2
])
def test_without_a_step_the_step_is_fmpys_round_number(tmp_path: Path, experiment: str,
                                                       samples: int, stop: float):
    fmu = with_experiment(tmp_path, experiment)
    ours = simulate(tmp_path, fmu)
    assert len(ours["time"]) == samples and ours["time"][-1] == stop
    assert_equals_fmpy(ours, fmu)


def test_given_times_override_the_experiment(tmp_path: Path):
    ours = simulate(tmp_path, fmus.path("pendulum_euler"), "--start-time", "1",
                    "--step-size", "0.1")
    assert ours["time"][0] == 1.0 and ours["time"][-1] == 3.0 and len(ours["time"]) == 21
    assert_equals_fmpy(ours, fmus.path("pendulum_euler"), start_time=1.0, output_interval=0.1)


def test_tolerance_reaches_the_fmu_as_in_fmpy(tmp_path: Path):
    """CVODE at a loose tolerance: the same numbers as FMPy given the same tolerance, and not
    those of the default."""
    fmu = fmus.path("pendulum_cvode")
    loose = simulate(tmp_path, fmu, "--tolerance", "1e-3", "--step-size", "0.05",
                     "--set", "theta0=1.0")
    assert_equals_fmpy(loose, fmu, relative_tolerance=1e-3, output_interval=0.05,
                       start_values={"theta0": 1.0})
    default = simulate(tmp_path, fmu, "--step-size", "0.05", "--set", "theta0=1.0")
    assert np.max(np.abs(loose["theta"] - default["theta"])) > 1e-6


def test_version(capsys: pytest.CaptureFixture[str]):
    assert main(["--version"]) == 0
    assert capsys.readouterr().out == f"syssimx {__version__}\n"


def test_an_error_without_a_message_still_says_what_failed(
        monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]):
    def fail(*args: object, **kwargs: object) -> None:
        raise AssertionError

    monkeypatch.setattr(FMUComponent, "__init__", fail)
    assert main(["simulate", "pendulum_euler"]) == 1
    assert capsys.readouterr().err == ("syssimx: error: AssertionError (with no message) in "
                                       "'syssimx simulate pendulum_euler'\n")


def test_bad_times_are_named(tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    assert main(["simulate", "pendulum_euler", "--start-time", "4"]) == 1
    assert capsys.readouterr().err == ("syssimx: error: need stop time > start time; got start "
                                       "4.0, stop 3.0\n")
    assert main(["simulate", "pendulum_euler", "--step-size", "-1"]) == 1
    assert capsys.readouterr().err == "syssimx: error: need step size > 0; got -1.0\n"
