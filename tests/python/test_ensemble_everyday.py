"""Ensembles that never lose work: a script without `if __name__ == "__main__":` fails once,
before any worker starts, showing the guard; the file a sweep writes is checked before it runs
and .nc is written by the ensemble extra's backend; progress is tqdm's, only on a terminal."""

from __future__ import annotations

import io
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
import syssimx

pytest.importorskip("distributed")
xr = pytest.importorskip("xarray")
from syssimx.cli import main  # noqa: E402
from syssimx.ensemble.main_guard import GUARD  # noqa: E402
from syssimx.ensemble.progress import ProgressBar  # noqa: E402
from syssimx.ensemble.result import WRITERS, netcdf_engine  # noqa: E402
from syssimx.errors import ConfigurationError  # noqa: E402
from syssimx.output_check import check_output  # noqa: E402

PYTHON_DIR = Path(syssimx.__file__).resolve().parents[1]

SCRIPT = """
from syssimx import FMUComponent, System, fmus
from syssimx.ensemble import sweep


def build():
    system = System("gain")
    system.add_component(FMUComponent("G", fmus.path("gain")))
    return system


{call}
"""


def run_script(tmp_path: Path, call: str) -> subprocess.CompletedProcess[str]:
    script = tmp_path / "my_sweep.py"
    script.write_text(textwrap.dedent(SCRIPT).format(call=call))
    environment = dict(os.environ)
    environment["PYTHONPATH"] = os.pathsep.join(
        [str(PYTHON_DIR), *filter(None, [environment.get("PYTHONPATH")])])
    if environment.get("SYSSIMX_BUILD_DIR"):  # the script runs in another folder
        environment["SYSSIMX_BUILD_DIR"] = str(Path(environment["SYSSIMX_BUILD_DIR"]).resolve())
    return subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                          env=environment, cwd=tmp_path, timeout=120)


def test_a_sweep_script_without_the_guard_fails_once_showing_it(tmp_path: Path):
    done = run_script(tmp_path, 'result = sweep(build, {"G.k": [1.0, 2.0]}, t0=0, tf=0.1, '
                                'dt=0.05, workers=1, progress=False)\nprint("finished")')
    assert done.returncode == 1
    assert "finished" not in done.stdout
    assert done.stderr.count("Traceback") == 1  # one error, no worker's traceback
    assert "Nanny" not in done.stderr
    assert "MissingMainGuardError: sweep() is run at the top level of my_sweep.py (line 12)" \
        in done.stderr
    assert f"    {GUARD}\n        result = sweep(...)" in done.stderr


def test_the_same_script_with_the_guard_runs(tmp_path: Path):
    done = run_script(tmp_path, f'{GUARD}\n    result = sweep(build, {{"G.k": [1.0, 2.0]}}, '
                                't0=0, tf=0.1, dt=0.05, workers=1, progress=False)\n'
                                '    print("finished", len(result), len(result.failed))')
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[-1] == "finished 2 0"


def test_the_writer_is_checked_before_the_members_run(tmp_path: Path, capsys):
    missing_folder = tmp_path / "no" / "out.nc"
    assert main(["sweep", "system.yaml", "--param", "P.theta0=1", "--quiet",
                 "-o", str(missing_folder)]) == 1
    # the system file is not even opened: the output is judged first
    assert capsys.readouterr().err == (f"syssimx: error: output {missing_folder}: the folder "
                                       f"{missing_folder.parent} does not exist\n")
    with pytest.raises(ConfigurationError, match=r"unknown format '\.xlsx'"):
        check_output(tmp_path / "out.xlsx", "output", WRITERS)


def test_netcdf_is_written_by_the_ensemble_extras_writer(tmp_path: Path, capsys):
    pytest.importorskip("scipy")
    assert netcdf_engine() == "scipy"
    system_file = tmp_path / "gain.yaml"
    system_file.write_text("system: {name: gain}\ncomponents:\n  - {name: G, fmu: gain}\n"
                           "run: {t0: 0.0, tf: 0.2, dt: 0.1}\n")
    output = tmp_path / "out.nc"
    assert main(["sweep", str(system_file), "--param", "G.k=1,2,3", "--workers", "1",
                 "--quiet", "--output-file", str(output)]) == 0
    assert output.read_bytes()[:4] == b"CDF\x02"  # netCDF3 (64-bit offsets), scipy's
    dataset = xr.open_dataset(output)
    assert list(dataset["G.k"].values) == [1.0, 2.0, 3.0]
    assert list(dataset["status"].values) == ["ok", "ok", "ok"]


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_progress_is_drawn_on_a_terminal_only():
    log = io.StringIO()
    bar = ProgressBar(3, stream=log)
    for failed in (0, 1, 0):
        bar.advance(1, failed)
    bar.close()
    assert log.getvalue() == ""  # a log file gets no carriage-return frames
    terminal = Terminal()
    bar = ProgressBar(3, stream=terminal)
    bar.advance(1, 0)
    bar.advance(2, 1)  # a task's block of two members, one failed
    bar.close()
    assert "3/3" in terminal.getvalue() and "1 failed" in terminal.getvalue()
