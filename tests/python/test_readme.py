"""The README's example runs as printed and finds the exact wall-hit time."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[2] / "README.md"
EXACT_EVENT_TIME = 0.46507759431173046


def test_readme_example_runs_and_locates_the_event(tmp_path, monkeypatch) -> None:
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), re.S)
    assert blocks, "the README has no Python example"
    monkeypatch.chdir(tmp_path)  # the example writes pendulum.png where it runs
    namespace: dict[str, object] = {}
    exec(compile(blocks[0], str(README), "exec"), namespace)
    result = namespace["result"]
    assert result.events[0].t == pytest.approx(EXACT_EVENT_TIME, abs=1e-8)
    assert result.statistics.localization_iterations <= 10
    assert (tmp_path / "pendulum.png").stat().st_size > 10_000


def test_the_readme_is_a_front_page():
    text = README.read_text()
    lines = text.splitlines()
    assert len(lines) < 155
    # the two commands come first
    first_block = re.search(r"```sh\n(.*?)```", text, re.S)
    assert first_block and text.index(first_block.group(0)) < text.index("\n## ")
    assert first_block.group(1).splitlines()[:2] == [
        line for line in first_block.group(1).splitlines()
        if line.startswith(("bash scripts/run-main.sh", "bash scripts/run-tests.sh"))]
    # the platforms are said before the first section, the install names the distribution and
    # the clash with SysSimX
    assert "Linux x86-64" in text[:text.index("\n## ")]
    install = text[text.index("## Install"):]
    assert "syssimx-engine" in install and "SysSimX 0.4.3" in install
    assert "side by side" in install and "libsundials-dev" in install


def test_the_readmes_links_point_at_files_of_the_repository():
    root = README.parent
    targets = re.findall(r"\]\(([^)#]+)\)", README.read_text())
    local = [target for target in targets if "://" not in target]
    assert len(local) >= 8
    missing = [target for target in local if not (root / target).exists()]
    assert not missing


def test_the_first_screen_says_how_syssimx_differs_from_the_other_tools():
    text = README.read_text()
    first_screen = text[:text.index("\n## ")]
    header = next(line for line in first_screen.splitlines() if line.startswith("| |"))
    assert [cell.strip() for cell in header.strip("|").split("|")][1:] == [
        "syssimx", "FMPy", "OMSimulator", "libcosim"]
    rows = {line.split("|")[1].strip() for line in first_screen.splitlines()
            if line.startswith("| ") and not line.startswith("| |")}
    assert {"events between FMUs", "algebraic loops", "step control", "ensembles"} <= rows
    # the syssimx claims link the pages with the measured figures
    assert "docs/performance/coupling-accuracy.md" in first_screen
    assert "docs/howitworks/tested-accuracy.md" in first_screen
