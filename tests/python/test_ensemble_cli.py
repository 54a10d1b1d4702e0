"""`syssimx sweep`: parameters from the command line, an embedded cluster of 2 workers, a
system from a Python file or a system file, results written, failed members listed."""

from __future__ import annotations

import importlib.util
import textwrap
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("distributed")
xr = pytest.importorskip("xarray")
from fixture_fmus import fmu_path  # noqa: E402
from syssimx.cli import main  # noqa: E402

SYSTEM_FUNCTION = """
from syssimx import FMUComponent, System


def build():
    failing = FMUComponent("F", {failing!r})
    failing.set_inputs({{"u": 3.0}})
    system = System("failing")
    system.add_component(failing)
    return system
"""


def test_sweep_of_a_function_in_a_python_file_lists_the_failed_member(tmp_path: Path,
                                                                      capsys) -> None:
    source = tmp_path / "my_system.py"  # not importable by the workers: sent by value
    source.write_text(textwrap.dedent(SYSTEM_FUNCTION).format(failing=fmu_path("failing")))
    output = tmp_path / "out.nc"
    code = main(["sweep", f"{source}:build", "--param", "F.failure=0",
                 "--param", "F.fail_time=0.25,2", "--tf", "0.5", "--dt", "0.05",
                 "--t0", "0", "--workers", "2", "-o", str(output)])
    captured = capsys.readouterr()
    assert code == 1
    assert f"wrote 2 members to {output}\n2 members, 1 ok, 1 failed, in " in captured.out
    assert ("member 0 (F.failure=0, F.fail_time=0.25) failed: SimulationError: component 'F': "
            "fmi2DoStep failed at t=0.25") in captured.out
    assert "\r" not in captured.err  # not a terminal: no progress bar frames
    assert "syssimx: error: 1 of 2 members failed (listed above)" in captured.err
    dataset = xr.open_dataset(output)
    assert list(dataset["status"].values) == ["failed", "ok"]
    assert list(dataset["F.fail_time"].values) == [0.25, 2.0]
    np.testing.assert_array_equal(dataset["F.y"].values[1], np.full(11, 3.0))


@pytest.mark.parametrize(("arguments", "message"), [
    (["--param", "theta0=1"], "expected Component.parameter=VALUES, got 'theta0=1'"),
    (["--param", "P.theta0=0:1:x"], "P.theta0: expected START:STOP:COUNT"),
    (["--param", "P.theta0=1", "--workers", "2", "--scheduler", "tcp://h:8786"],
     "not allowed with argument"),
])
def test_bad_sweep_usage_exits_2_naming_the_argument(arguments: list[str], message: str,
                                                     capsys) -> None:
    assert main(["sweep", "system.yaml", *arguments]) == 2
    assert message in capsys.readouterr().err


def test_not_a_system_is_one_clear_line(capsys) -> None:
    assert main(["sweep", "pendulum", "--param", "P.theta0=1", "--quiet"]) == 1
    assert capsys.readouterr().err == (
        "syssimx: error: 'pendulum' is neither a system file (.yaml, .yml, .json) nor "
        "MODULE:FUNCTION or FILE.py:FUNCTION\n")


SYSTEM_FILE = """
system: {name: wall}
components:
  - name: P
    fmu: pendulum_cvode
    parameters: {cvode_relative_tolerance: 1.0e-10}
run: {t0: 0.0, tf: 0.4, dt: 0.05}
"""


@pytest.mark.skipif(importlib.util.find_spec("syssimx.system.loader") is None,
                    reason="the system file loader (syssimx.system.loader) is not present")
def test_sweep_of_a_system_file_takes_the_run_from_the_file(tmp_path: Path, capsys) -> None:
    description = tmp_path / "wall.yaml"
    description.write_text(textwrap.dedent(SYSTEM_FILE))
    output = tmp_path / "out.csv"
    code = main(["sweep", str(description), "--param", "P.theta0=0.1:0.3:3", "--workers", "2",
                 "--quiet", "-o", str(output)])
    assert code == 0, capsys.readouterr().err
    assert "3 members, 3 ok, 0 failed" in capsys.readouterr().out
    import pandas as pd

    table = pd.read_csv(output)
    assert sorted(set(table["P.theta0"])) == pytest.approx([0.1, 0.2, 0.3])
    assert table.groupby("member")["time"].max().tolist() == [0.4] * 3
    assert table[table.time == 0.0]["P.theta"].tolist() == pytest.approx([0.1, 0.2, 0.3])
