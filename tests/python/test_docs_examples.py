"""Every Python example of the documentation's Markdown pages runs as printed: the ```python
blocks of a page, top to bottom, as one script run in a temporary folder — as a reader who
copies them runs them (so an ensemble's `if __name__ == "__main__":` guard works as it does for
them). Notebook pages (a `kernelspec` in their front matter) are executed by the documentation
build instead."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
import syssimx
from syssimx import _paths

DOCS = Path(__file__).resolve().parents[2] / "docs"
PYTHON_BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)
# the syssimx this test process imports (the source tree with a build, or the installed package)
PYTHON_DIR = Path(syssimx.__file__).resolve().parents[1]


def is_notebook(text: str) -> bool:
    front_matter = re.match(r"---\n(.*?)\n---\n", text, re.S)
    return bool(front_matter and "kernelspec" in front_matter.group(1))


def pages_with_examples() -> list[Path]:
    pages = []
    for page in sorted(DOCS.rglob("*.md")):
        text = page.read_text(encoding="utf-8")
        if not is_notebook(text) and PYTHON_BLOCK.search(text):
            pages.append(page)
    return pages


def script_of(text: str) -> str:
    """The page's Python blocks at their own line numbers (the lines between are blank), so
    that a traceback's line is the page's."""
    lines = [""] * (text.count("\n") + 1)
    for match in PYTHON_BLOCK.finditer(text):
        first = text.count("\n", 0, match.start(1))
        for offset, line in enumerate(match.group(1).splitlines()):
            lines[first + offset] = line
    return "\n".join(lines) + "\n"


def test_the_documentation_has_python_examples_outside_the_notebooks():
    assert len(pages_with_examples()) >= 3


def test_a_script_keeps_the_pages_line_numbers():
    text = "# Title\n\n```python\nx = 1\n```\n\ntext\n\n```python\nraise ValueError(x)\n```\n"
    assert script_of(text).splitlines()[3] == "x = 1"
    assert script_of(text).splitlines()[9] == "raise ValueError(x)"


@pytest.mark.parametrize("page", pages_with_examples(),
                         ids=lambda page: str(page.relative_to(DOCS)))
def test_the_examples_of_a_page_run(page: Path, tmp_path):
    script = tmp_path / page.with_suffix(".py").name
    script.write_text(script_of(page.read_text(encoding="utf-8")), encoding="utf-8")
    environment = dict(os.environ, MPLBACKEND="Agg")  # figures are drawn, never shown
    environment["PYTHONPATH"] = os.pathsep.join(
        [str(PYTHON_DIR), *filter(None, [environment.get("PYTHONPATH")])])
    build = _paths.build_dir()  # a relative one means relative to where the tests started
    if build is not None:
        environment["SYSSIMX_BUILD_DIR"] = str(build)
    run = subprocess.run([sys.executable, script.name], cwd=tmp_path, env=environment,
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, (f"{page.relative_to(DOCS)}: the examples failed (line numbers "
                                 f"are the page's):\n{run.stderr[-4000:]}")
