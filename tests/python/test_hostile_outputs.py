"""Nothing computed is lost (issue 20, items 11, 12, 17): an output that cannot be written is
refused before the run; a write that fails afterwards keeps the results (a fallback file the
message names); every output file appears whole or not at all; Ctrl-C keeps what was finished
(on the exception in the API; written by the command line, which exits 130)."""

from __future__ import annotations

import csv
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from syssimx import FMUComponent, System, fmus
from syssimx.atomic_file import atomic_path
from syssimx.cli import main
from syssimx.errors import ConfigurationError, RunInterrupted
from syssimx.output_check import check_output
from syssimx.system import system as system_module

CLI = [sys.executable, "-c", "import sys; from syssimx.cli import main; sys.exit(main())"]


def forbid_running(monkeypatch: pytest.MonkeyPatch) -> None:
    def refuse(*args: object, **kwargs: object) -> None:
        raise AssertionError("the run started before its output was checked")

    monkeypatch.setattr(system_module.System, "run", refuse)


@pytest.mark.parametrize("command", [
    ["simulate", "pendulum_euler", "--stop-time", "0.1", "-o", "{missing}/out.csv"],
    ["simulate", "pendulum_euler", "--stop-time", "0.1", "--plot", "{missing}/out.png"],
    ["run", "{examples}/pendulum_wall.yaml", "-o", "{missing}/out.csv"],
])
def test_an_output_in_a_missing_folder_is_refused_before_the_run(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str],
        command: list[str]):
    forbid_running(monkeypatch)
    missing = tmp_path / "missing"
    examples = Path(__file__).resolve().parents[2] / "examples"
    argv = [part.format(missing=missing, examples=examples) for part in command]
    assert main(argv) == 1
    error = capsys.readouterr().err
    assert f"the folder {missing} does not exist" in error


def test_a_sweep_output_is_checked_before_any_member_runs(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]):
    from syssimx.ensemble import command

    def refuse(*args: object, **kwargs: object) -> None:
        raise AssertionError("members ran before the output was checked")

    monkeypatch.setattr(command, "sweep", refuse)
    system = Path(__file__).resolve().parents[2] / "examples" / "pendulum_wall.yaml"
    for output, message in ((tmp_path / "missing" / "out.nc", "does not exist"),
                            (tmp_path / "out.xlsx", "unknown format '.xlsx'")):
        assert main(["sweep", str(system), "--param", "P.theta0=0.1,0.2", "-o",
                     str(output)]) == 1
        assert message in capsys.readouterr().err


def test_a_writer_that_is_not_installed_is_named(tmp_path: Path,
                                                 monkeypatch: pytest.MonkeyPatch):
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name in ("pyarrow", "fastparquet")
                        else real(name, *a))
    with pytest.raises(ConfigurationError, match=r"writing \.parquet needs pyarrow or "
                       "fastparquet, which is not installed"):
        check_output(tmp_path / "out.parquet")
    read_only = tmp_path / "read-only"
    read_only.mkdir()
    read_only.chmod(0o500)
    try:
        if os.access(read_only, os.W_OK):
            pytest.skip("running as a user who writes anywhere (root)")
        with pytest.raises(ConfigurationError, match="is not writable"):
            check_output(read_only / "out.csv")
    finally:
        read_only.chmod(0o700)


def test_a_write_that_fails_after_the_run_keeps_the_results(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]):
    """The folder vanishes while the run goes on: the results go to a fallback file that the
    message names."""
    folder = tmp_path / "gone"
    folder.mkdir()
    run = system_module.System.run

    def run_then_remove_the_folder(self: System, *args: object, **kwargs: object) -> object:
        result = run(self, *args, **kwargs)
        folder.rmdir()
        return result

    monkeypatch.setattr(system_module.System, "run", run_then_remove_the_folder)
    assert main(["simulate", "pendulum_euler", "--stop-time", "0.2", "-o",
                 str(folder / "out.csv")]) == 1
    error = capsys.readouterr().err
    assert f"cannot write {folder / 'out.csv'}" in error
    fallback = Path(error.split("the results were written to ")[1].split(" instead")[0])
    try:
        with fallback.open() as stream:
            rows = list(csv.reader(stream))
        assert rows[0][0] == "time" and float(rows[-1][0]) == pytest.approx(0.2)
    finally:
        fallback.unlink()


def test_a_failed_write_leaves_the_old_file_and_no_part(tmp_path: Path):
    """Before: the target was truncated and left with the rows written so far."""
    target = tmp_path / "out.csv"
    target.write_text("the previous results\n")

    def rows() -> object:
        for k in range(1000):
            if k == 500:
                raise OSError("No space left on device")
            yield ("P", "theta", float(k), float(k), "rad")

    from syssimx.system import csv_export

    with pytest.raises(OSError, match="No space left"):
        csv_export._write(target, [csv_export.LONG_HEADER], rows())
    assert target.read_text() == "the previous results\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.csv"]


def test_an_atomic_file_gets_the_mode_of_a_direct_write(tmp_path: Path):
    direct = tmp_path / "direct.txt"
    direct.write_text("x")
    with atomic_path(tmp_path / "atomic.txt") as temporary:
        temporary.write_text("x")
    assert (tmp_path / "atomic.txt").stat().st_mode == direct.stat().st_mode


def test_sigterm_while_writing_never_leaves_a_truncated_file(tmp_path: Path):
    """Before: SIGTERM during a big CSV left a shorter file that ended on a whole row."""
    target = tmp_path / "big.csv"
    script = textwrap.dedent(f"""
        import numpy as np
        from syssimx.system.csv_export import write_wide
        t = np.linspace(0.0, 1.0, 3_000_001)
        write_wide({str(target)!r}, t, {{"y": t, "z": -t}}, {{}})
    """)
    process = subprocess.Popen([sys.executable, "-c", script])
    try:
        deadline = time.monotonic() + 60
        while not any(".partial" in p.name for p in tmp_path.iterdir()):
            assert process.poll() is None and time.monotonic() < deadline
            time.sleep(0.01)
        time.sleep(0.2)  # well inside the write
        process.send_signal(signal.SIGTERM)
        assert process.wait(timeout=60) == -signal.SIGTERM
    finally:
        process.kill()
    assert not target.exists()


def slow_pendulum(step: float = 1e-7) -> System:
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.set_parameters(euler_step_size=step)
    system = System("slow")
    system.add_component(pendulum)
    return system


def interrupt_after(seconds: float) -> threading.Timer:
    timer = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    return timer


def test_ctrl_c_in_a_run_hands_over_what_was_finished():
    system = slow_pendulum()
    system.initialize(0.0)
    timer = interrupt_after(0.5)
    try:
        with pytest.raises(RunInterrupted) as caught:
            system.run(0.0, 1000.0, 1e-3)
    finally:
        timer.cancel()
    assert isinstance(caught.value, KeyboardInterrupt) and caught.value.partial
    partial = caught.value.partial_result
    t, values = partial["P"]
    assert 0.0 < t[-1] < 1000.0 and partial.tf == t[-1]
    np.testing.assert_array_equal(t, system.get_history()["P"][0])
    assert np.all(np.isfinite(values["theta"]))


def test_ctrl_c_in_simulate_writes_what_was_finished_and_exits_130(tmp_path: Path):
    output = tmp_path / "out.csv"
    process = subprocess.Popen(
        [*CLI, "simulate", "pendulum_euler", "--stop-time", "1000", "--step-size", "1e-3",
         "--set", "euler_step_size=1e-7", "-o", str(output)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(4.0)  # the imports, then some steps
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=60)
    assert process.returncode == 130, err
    assert "Traceback" not in err
    assert len(err.strip().splitlines()) == 1 and err.startswith("syssimx: interrupted")
    assert f"to {output}" in out
    with output.open() as stream:
        rows = list(csv.reader(stream))
    assert rows[0][0] == "time" and 1 < len(rows) and 0.0 < float(rows[-1][0]) < 1000.0


def test_ctrl_c_in_a_sweep_keeps_the_finished_members(monkeypatch: pytest.MonkeyPatch):
    """Before: KeyboardInterrupt, and the finished members were lost. Ctrl-C comes as the
    second quick member's result arrives (a fixed delay raced the cluster's start)."""
    pytest.importorskip("distributed")
    from syssimx.ensemble import progress, sweep

    advance = progress.ProgressBar.advance

    def advance_then_interrupt(bar: progress.ProgressBar, done: int, failed: int) -> None:
        advance(bar, done, failed)
        if bar.done == 2:
            os.kill(os.getpid(), signal.SIGINT)

    monkeypatch.setattr(progress.ProgressBar, "advance", advance_then_interrupt)
    timer = interrupt_after(300.0)  # a backstop: the slow member alone would run for hours
    try:
        with pytest.raises(RunInterrupted) as caught:
            sweep(slow_pendulum, {"P.euler_step_size": [1e-4, 1e-4, 1e-9]}, t0=0.0, tf=1.0, dt=1e-3,
                  workers=2, progress=False)
    finally:
        timer.cancel()
    members = caught.value.partial_result.members
    assert [m.ok for m in members] == [True, True, False]
    assert members[0].time[-1] == 1.0
    assert members[2].error_type == "KeyboardInterrupt"
    assert "interrupted" in members[2].error


def test_an_ssp_archive_that_fails_while_written_leaves_the_old_file(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    """The archive is written under a temporary name: a failure while the FMUs are copied in
    (a full disk) leaves the previous archive, and no part."""
    import zipfile

    from syssimx.ssp import write_ssp

    system = System("s")
    system.add_component(FMUComponent("P", fmus.path("pendulum_euler")))
    target = tmp_path / "s.ssp"
    target.write_bytes(b"the previous archive")

    def full_disk(self: zipfile.ZipFile, *args: object, **kwargs: object) -> None:
        raise OSError("No space left on device")

    monkeypatch.setattr(zipfile.ZipFile, "write", full_disk)
    with pytest.raises(OSError, match="No space left"):
        write_ssp(system, target)
    assert target.read_bytes() == b"the previous archive"
    assert [p.name for p in tmp_path.iterdir()] == ["s.ssp"]
