"""Writing a command's results (issue 34, item 6): Ctrl-C while the file is written lets the
write finish (exit 130 after it); a long write shows a bar on a terminal; `run -o --wide`
writes FMPy's wide table, as `simulate -o` does."""

from __future__ import annotations

import csv
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from syssimx.cli import main, result_file
from syssimx.cli import run as run_command

CLI = [sys.executable, "-c", "import sys; from syssimx.cli import main; sys.exit(main())"]


def pendulum_description(folder: Path, tf: float) -> Path:
    path = folder / "long.yaml"
    path.write_text("system: {name: long}\n"
                    "components:\n  - {name: P, fmu: pendulum_euler}\n"
                    f"run: {{t0: 0.0, tf: {tf}, dt: 0.001}}\n")
    return path


def test_ctrl_c_while_the_results_are_written_keeps_them(tmp_path: Path):
    """Before: the half-written file was removed, nothing kept of a finished run."""
    output = tmp_path / "out.csv"
    process = subprocess.Popen([*CLI, "run", str(pendulum_description(tmp_path, 500.0)), "-o",
                                str(output)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True)
    try:
        deadline = time.monotonic() + 120
        while not any(".partial" in p.name for p in tmp_path.iterdir()):
            assert process.poll() is None and time.monotonic() < deadline
            time.sleep(0.01)
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=120)
    finally:
        process.kill()
    assert process.returncode == 130, err
    assert "finishing the write of" in err and "Traceback" not in err
    assert f"Results written to {output}" in out
    with output.open() as stream:
        rows = sum(1 for _ in stream)
    assert rows == 1 + 3 * 500_001  # the header, then each of 3 outputs at every sample


def test_run_writes_fmpys_wide_table_on_request(tmp_path: Path):
    description = pendulum_description(tmp_path, 0.01)
    long, wide = tmp_path / "long.csv", tmp_path / "wide.csv"
    assert main(["run", str(description), "-o", str(long)]) == 0
    assert main(["run", str(description), "-o", str(wide), "--wide"]) == 0
    with wide.open() as stream:
        rows = list(csv.reader(stream))
    assert rows[0] == ["time", "P.theta", "P.omega", "P.alpha"]
    with long.open() as stream:
        cells = {(row[1], row[2]): row[4] for row in list(csv.reader(stream))[1:]}
    assert len(rows) == 1 + 11
    for row in rows[1:]:
        assert row[1:] == [cells[(port, row[0])] for port in ("theta", "omega", "alpha")]


def test_a_long_write_shows_a_bar(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                  capsys: pytest.CaptureFixture[str]):
    """The bar a terminal shows (drawn here at once, on the captured stderr)."""
    monkeypatch.setattr(result_file, "BAR_DELAY", 0.0)
    monkeypatch.setattr(run_command, "_write_results", _with_bar(run_command._write_results))
    assert main(["run", str(pendulum_description(tmp_path, 1.0)), "-o",
                 str(tmp_path / "out.csv")]) == 0
    assert "writing " in capsys.readouterr().err


def _with_bar(write: object) -> object:
    def write_with_bar(result: object, args: object, bar: bool) -> object:
        return write(result, args, True)  # type: ignore[operator]
    return write_with_bar
