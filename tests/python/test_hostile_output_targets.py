"""What an output path may be (issue 34, item 1): a symbolic link is written through (its file
replaced, the link kept); a device or a FIFO is written directly, never replaced by a regular
file; a write that fails there (a full device) fails the command. The devices are made by the
test in a private mount namespace on a tmpfs of its own, never the machine's /dev."""

from __future__ import annotations

import csv
import os
import shutil
import stat
import subprocess
import sys
import textwrap
import threading
from pathlib import Path

import pytest
from syssimx import ConfigurationError, FMUComponent, System, fmus
from syssimx.cli import main

CLI = [sys.executable, "-c", "import sys; from syssimx.cli import main; sys.exit(main())"]
SIMULATE = ["simulate", "pendulum_euler", "--stop-time", "0.1"]


def test_a_symlinked_output_is_written_through_the_link(tmp_path: Path):
    """Before: the link became a plain file and the file it named kept the old results."""
    results = tmp_path / "kept" / "results.csv"
    results.parent.mkdir()
    results.write_text("the previous results\n")
    link = tmp_path / "latest.csv"
    link.symlink_to(results)
    assert main([*SIMULATE, "-o", str(link)]) == 0
    assert link.is_symlink() and link.resolve() == results
    with results.open() as stream:
        rows = list(csv.reader(stream))
    assert rows[0][0] == "time" and float(rows[-1][0]) == pytest.approx(0.1)
    assert sorted(p.name for p in results.parent.iterdir()) == ["results.csv"]


def test_a_fifo_output_reaches_its_reader_and_stays_a_fifo(tmp_path: Path):
    """Before: the FIFO was replaced by a regular file; its reader got nothing."""
    fifo = tmp_path / "results.fifo"
    os.mkfifo(fifo)
    received: list[str] = []
    reader = threading.Thread(target=lambda: received.append(fifo.read_text()))
    reader.start()
    try:
        assert main(["run", str(Path(__file__).resolve().parents[2] / "examples" /
                                  "pendulum_wall.yaml"), "-o", str(fifo)]) == 0
    finally:
        if reader.is_alive():  # the command failed before opening it: let the reader go
            with open(fifo, "w"):
                pass
        reader.join(timeout=60)
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    rows = list(csv.reader(received[0].splitlines()))
    assert rows[0] == ["component", "port", "time", "micro", "value", "unit"] and len(rows) > 20


def test_a_link_to_standard_output_writes_to_it(tmp_path: Path):
    """`-o /dev/stdout`, made here as a link of the test's own to the process's fd 1 (a pipe):
    the CSV comes out on the pipe and the link stays."""
    link = tmp_path / "stdout.csv"
    link.symlink_to("/proc/self/fd/1")
    done = subprocess.run([*CLI, *SIMULATE, "-o", str(link)], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("time,theta,omega,alpha\n0.0,")
    assert link.is_symlink()


def test_a_refused_run_leaves_an_existing_stream_file_alone(tmp_path: Path):
    """Before: stream_to was opened (and truncated) before the engine refused dt < 0."""
    streamed = tmp_path / "run.csv"
    streamed.write_text("the previous run\n")
    system = System("s")
    system.add_component(FMUComponent("P", fmus.path("pendulum_euler")))
    system.initialize(0.0)
    with pytest.raises(Exception, match="dt must be positive"):
        system.run(0.0, 1.0, -0.1, stream_to=streamed)
    assert streamed.read_text() == "the previous run\n"


@pytest.mark.parametrize("suffix", [".nc", ".parquet"])
def test_a_stream_that_seeks_is_refused_into_a_fifo_before_the_run(tmp_path: Path, suffix: str):
    """Before: NetCDF failed at the end of the run with io.UnsupportedOperation (the samples
    computed, then lost), Parquet with 'lseek failed'. The FIFO stays and nothing is run."""
    fifo = tmp_path / f"run{suffix}"
    os.mkfifo(fifo)
    system = System("s")
    system.add_component(FMUComponent("P", fmus.path("pendulum_euler")))
    system.initialize(0.0)
    with pytest.raises(ConfigurationError, match=f"cannot stream a run to {fifo}: a {suffix} "
                                                 "file is written with seeks, which a FIFO"):
        system.run(0.0, 1.0, 0.01, stream_to=fifo)
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    assert system.get_history()["P"][0][-1] == 0.0  # not run


def _in_private_mount_namespace(script: str, folder: Path) -> subprocess.CompletedProcess[str]:
    """Runs the shell `script` in a mount namespace of its own with a fresh tmpfs on `folder`
    (devices made there with mknod exist for that process only); skips where that is not
    allowed (not root, no unshare)."""
    if shutil.which("unshare") is None or os.geteuid() != 0:
        pytest.skip("making device nodes needs root and unshare (a private mount namespace)")
    probe = subprocess.run(["unshare", "-m", "--propagation", "private", "true"],
                           capture_output=True)
    if probe.returncode != 0:
        pytest.skip(f"no private mount namespace here: {probe.stderr.decode().strip()}")
    whole = f"mount -t tmpfs syssimx-test {folder} && {script}"
    return subprocess.run(["unshare", "-m", "--propagation", "private", "sh", "-c", whole],
                          capture_output=True, text=True, timeout=300)


def test_device_outputs_are_written_into_not_replaced(tmp_path: Path):
    """Before (as root): `-o null` left a CSV where the device node was, and `-o full` (the
    device that answers every write with ENOSPC) succeeded the same way."""
    folder = tmp_path / "devices"
    folder.mkdir()
    command = " ".join(f"'{part}'" for part in [*CLI, *SIMULATE])
    script = textwrap.dedent(f"""\
        cd {folder} && mknod null c 1 3 && mknod full c 1 7 && cd - >/dev/null || exit 99
        export TMPDIR={folder}  # the fallback file of the failed write stays on the tmpfs
        {command} -o {folder}/null >/dev/null 2>{folder}/null.err; echo "null $?"
        {command} -o {folder}/full >/dev/null 2>{folder}/full.err; echo "full $?"
        stat -c '%F' {folder}/null {folder}/full
        cat {folder}/full.err
    """)
    done = _in_private_mount_namespace(script, folder)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[:4] == ["null 0", "full 1", "character special file",
                         "character special file"], done.stdout
    assert "No space left on device" in lines[4], done.stdout
