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
