"""`syssimx run CONFIG` and `syssimx describe CONFIG`: SysSimX's commands, their output parsed
back and compared with the same system built in Python."""

from __future__ import annotations

import csv
import re
import sys
from pathlib import Path

import coupled_pendulums
import pytest
from syssimx import GaussSeidelAlgorithm
from syssimx.cli import main
from syssimx.system.loader import build_system

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
COMPLETED = re.compile(r"Completed '(?P<name>[^']*)': t in \[(?P<t0>\S+), (?P<tf>\S+)\] s, "
                       r"dt = (?P<dt>\S+) s, algorithm = (?P<algorithm>\w+), "
                       r"wall time = (?P<wall>\d+\.\d{3}) s")


def read_long(path: Path) -> dict[tuple[str, str], tuple[list[float], list[float], str]]:
    """{(component, port): (times, values, unit)} of a long CSV."""
    with path.open(newline="") as stream:
        rows = list(csv.reader(stream))
    assert rows[0] == ["component", "port", "time", "micro", "value", "unit"]
    table: dict[tuple[str, str], tuple[list[float], list[float], str]] = {}
    for component, port, time, _, value, unit in rows[1:]:
        times, values, _ = table.setdefault((component, port), ([], [], unit))
        times.append(float(time))
        values.append(float(value))
    return table


def test_run_prints_syssimx_summary_and_writes_the_long_csv(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    out = tmp_path / "coupled.csv"
    assert main(["run", str(EXAMPLES / "coupled_pendulums.yaml"), "--tf", "0.5",
                 "-o", str(out)]) == 0
    captured = capsys.readouterr()
    first, second = captured.out.splitlines()
    summary = COMPLETED.fullmatch(first)
    assert summary is not None, first
    assert summary.group("name", "t0", "tf", "dt", "algorithm") == (
        "coupled pendulums", "0.0", "0.5", "0.01", "GaussSeidelAlgorithm")
    assert second == f"Results written to {out}"
    assert captured.err == ""  # not a terminal: no progress bar

    python_built = coupled_pendulums.build(GaussSeidelAlgorithm())
    python_built.initialize(0.0)
    reference = python_built.run(0.0, 0.5, 0.01)
    table = read_long(out)
    expected_keys = [(name, port) for name in ("P1", "P2", "Spring")
                     for port in reference[name][1]]
    assert list(table) == expected_keys
    for (name, port), (times, values, unit) in table.items():
        t, columns = reference[name]
        assert times == t.tolist()
        assert values == columns[port].tolist()  # every digit written and read back
        assert unit == (reference.units[name][port] or "")
    assert table[("P1", "theta")][2] == "rad"


def test_run_overrides_the_description_and_quiet_prints_only_the_summary(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    out = tmp_path / "quickstart.csv"
    argv = ["run", str(EXAMPLES / "quickstart.json"), "--t0", "0", "--tf", "2", "--dt", "0.5",
            "-o", str(out), "--quiet", "--allow-module", "quickstart"]
    assert main(argv) == 0
    captured = capsys.readouterr()
    summary = COMPLETED.fullmatch(captured.out.splitlines()[0])
    assert summary is not None
    assert summary.group("name", "t0", "tf", "dt", "algorithm") == (
        "QuickstartSystem", "0.0", "2.0", "0.5", "GaussSeidelAlgorithm")
    assert captured.err == ""
    table = read_long(out)
    # Euler of y' = t with h = 0.5: 0.5 * (0 + 0.5 + 1.0 + 1.5) = 1.5
    assert table[("Integrator", "y")][:2] == ([0.0, 0.5, 1.0, 1.5, 2.0],
                                               [0.0, 0.0, 0.25, 0.75, 1.5])
    assert table[("LinearSource", "y")][1] == [0.0, 0.5, 1.0, 1.5, 2.0]


def test_run_without_output_writes_no_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                           capsys: pytest.CaptureFixture[str]):
    monkeypatch.chdir(tmp_path)
    assert main(["run", str(EXAMPLES / "quickstart.yaml"), "--allow-module", "quickstart"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 1 and lines[0].startswith("Completed 'QuickstartSystem': t in [0.0, 5.0]")
    assert list(tmp_path.iterdir()) == []


def test_component_classes_are_found_in_the_working_directory(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]):
    """As with SysSimX's command line: the module beside neither the description nor on
    sys.path, but in the directory the command runs in."""
    work, configs = tmp_path / "work", tmp_path / "configs"
    work.mkdir()
    configs.mkdir()
    (work / "my_blocks.py").write_text((EXAMPLES / "quickstart.py").read_text())
    config = configs / "system.yaml"
    config.write_text((EXAMPLES / "quickstart.yaml").read_text()
                      .replace('"quickstart:', '"my_blocks:'))
    monkeypatch.chdir(work)
    monkeypatch.setattr(sys, "path", [p for p in sys.path if p not in ("", str(work))])
    assert main(["run", str(config), "--quiet", "--allow-module", "my_blocks"]) == 0
    assert capsys.readouterr().out.startswith("Completed 'QuickstartSystem'")
    assert str(work) not in sys.path  # only while the command runs


def test_describe_prints_the_structural_report(capsys: pytest.CaptureFixture[str]):
    config = EXAMPLES / "pendulum_wall.yaml"
    assert main(["describe", str(config)]) == 0
    assert capsys.readouterr().out == build_system(config).describe() + "\n"


def test_describe_initialize_initializes_first(capsys: pytest.CaptureFixture[str]):
    config = EXAMPLES / "coupled_pendulums.yaml"
    assert main(["describe", str(config), "--initialize"]) == 0
    system = build_system(config)
    system.initialize(0.0)
    assert capsys.readouterr().out == system.describe() + "\n"


def test_a_bad_description_is_one_line_naming_file_and_entry(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    config = tmp_path / "bad.yaml"
    config.write_text("system: {name: S}\ncomponents: []\nrun: {t0: 0, tf: 1}\n")
    assert main(["run", str(config)]) == 1
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err.startswith(f"syssimx: error: {config}")
    assert "run" in captured.err and "dt" in captured.err
    assert len(captured.err.splitlines()) == 1


def test_run_accepts_every_algorithm_a_description_accepts(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    """One table of algorithms: `--algorithm ijcsa` runs what `algorithm: {type: ijcsa}` runs."""
    out = tmp_path / "ijcsa.csv"
    assert main(["run", str(EXAMPLES / "coupled_pendulums.yaml"), "--tf", "0.2",
                 "--algorithm", "ijcsa", "-o", str(out)]) == 0
    summary = COMPLETED.fullmatch(capsys.readouterr().out.splitlines()[0])
    assert summary is not None and summary.group("algorithm") == "IJCSAAlgorithm"
    config = tmp_path / "ijcsa.yaml"
    config.write_text((EXAMPLES / "coupled_pendulums.yaml").read_text()
                      .replace("{type: gauss_seidel}", "{type: ijcsa}"))
    described = build_system(config)
    described.initialize(0.0)
    reference = described.run(0.0, 0.2, 0.01)
    assert reference.algorithm == "IJCSAAlgorithm"
    for (name, port), (times, values, _) in read_long(out).items():
        assert times == reference[name][0].tolist()
        assert values == reference[name][1][port].tolist()
