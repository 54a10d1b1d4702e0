"""Runs too long to make (issue 34, item 9): an infinite or astronomic stop time is refused
before anything runs, naming the limit; with an input file the communication points are made
one at a time and --timeout holds; running out of memory is said as such."""

from __future__ import annotations

import resource
import subprocess
import sys
from pathlib import Path

import pytest
from syssimx.cli import main
from syssimx.system import system as system_module

CLI = [sys.executable, "-c", "import sys; from syssimx.cli import main; sys.exit(main())"]
SIGNALS = "time,torque\n0,0\n0.4,2\n0.4,-1\n1,3\n"
MEMORY_CAP = 3 << 30  # bytes of address space: before, the points' list reached it in seconds


def capped() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_CAP, MEMORY_CAP))


def simulate_with_input(tmp_path: Path, *options: str, timeout: float = 120
                        ) -> subprocess.CompletedProcess[str]:
    signals = tmp_path / "signals.csv"
    signals.write_text(SIGNALS)
    return subprocess.run([*CLI, "simulate", "pendulum_euler", "--input", str(signals),
                           *options], capture_output=True, text=True, timeout=timeout,
                          preexec_fn=capped)


@pytest.mark.parametrize(("stop", "message"), [
    ("1e300", "takes 1e+302 steps; syssimx runs at most 1e+12 steps"),
    ("inf", "--stop-time must be a finite number of seconds; got inf"),
])
def test_an_endless_stop_time_is_refused_naming_the_limit(tmp_path: Path, stop: str,
                                                          message: str):
    """Before: the list of communication points grew until memory ran out ("MemoryError
    (with no message)"), --timeout unheeded."""
    done = simulate_with_input(tmp_path, "--stop-time", stop, "--step-size", "0.01",
                               "--timeout", "2")
    assert done.returncode == 1
    assert done.stderr.startswith("syssimx: error: ") and message in done.stderr, done.stderr


def test_a_long_run_with_an_input_file_stops_at_its_timeout(tmp_path: Path):
    """1e11 steps: before, every point was listed before the first step was run."""
    output = tmp_path / "out.csv"
    done = simulate_with_input(tmp_path, "--stop-time", "1e9", "--step-size", "0.01",
                               "--timeout", "2", "-o", str(output), timeout=60)
    assert done.returncode == 1 and "timeout" in done.stderr, done.stderr
    assert len(output.read_text().splitlines()) > 1000


def test_running_out_of_memory_is_said_so(monkeypatch: pytest.MonkeyPatch,
                                          capsys: pytest.CaptureFixture[str]):
    def out_of_memory(*args: object, **kwargs: object) -> None:
        raise MemoryError

    monkeypatch.setattr(system_module.System, "run", out_of_memory)
    assert main(["simulate", "pendulum_euler", "--stop-time", "0.1"]) == 1
    error = capsys.readouterr().err
    assert error.startswith("syssimx: error: out of memory in 'syssimx simulate'")
    assert "--stop-time" in error
