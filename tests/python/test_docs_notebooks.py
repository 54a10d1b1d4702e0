"""What the documentation shows is what the code does: every page with Python code is a MyST
notebook, which the documentation build (MyST-NB, `nb_execution_mode = "force"`) executes at
every build and fails on any error, so its outputs and figures are those of this syssimx; no
page shows Python code that nothing runs (but for a cell tagged skip-execution that needs an FMU
file syssimx does not ship); every tutorial draws a figure."""

from __future__ import annotations

import re
from html.parser import HTMLParser
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
# where the test command's documentation step builds the site, before it runs pytest
BUILT_SITE = ROOT / "build" / "docs" / "html"

FRONT_MATTER = re.compile(r"---\n(.*?)\n---\n", re.S)
# a fenced block a reader takes for Python: ```python, ```py, ```python3, ```ipython3, ...
PYTHON_FENCE = re.compile(r"^\s*(```+|~~~+)\s*\{?(?:i?python3?|py)\}?\s*$", re.M)
CODE_CELL = re.compile(r"^```+\s*\{code-cell\}[^\n]*\n(.*?)^```", re.S | re.M)
SKIPPED = re.compile(r"^:tags:.*\bskip-execution\b", re.M)
# a file name of an FMU the reader supplies, as a string in the code
OWN_FMU = re.compile(r"\.fmu[\"']")
# a code cell that draws: pyplot's figures, or a syssimx result's plot
DRAWS = re.compile(r"\bplt\.(show|subplots|figure|plot)\(|\.plot\(")


def is_notebook(text: str) -> bool:
    front_matter = FRONT_MATTER.match(text)
    return bool(front_matter and "kernelspec" in front_matter.group(1))


def pages(docs: Path) -> dict[str, str]:
    return {str(page.relative_to(docs)): page.read_text(encoding="utf-8")
            for page in sorted(docs.rglob("*.md"))}


def skips_without_reason(text: str) -> bool:
    return any(SKIPPED.search(cell) and not OWN_FMU.search(cell)
               for cell in CODE_CELL.findall(text))


def pages_with_unexecuted_python(docs: Path) -> list[str]:
    """Pages showing Python that the build does not run: a Python block (```python), code cells
    in a page without a kernel (MyST-NB executes only pages with one), a cell tagged
    skip-execution that needs no FMU file of the reader's."""
    return [name for name, text in pages(docs).items()
            if PYTHON_FENCE.search(text) or skips_without_reason(text)
            or (CODE_CELL.search(text) and not is_notebook(text))]


def tutorials_without_a_figure(docs: Path) -> list[str]:
    return [name for name, text in pages(docs / "tutorials").items()
            if name != "index.md"
            and not any(DRAWS.search(cell) for cell in CODE_CELL.findall(text))]


class _Images(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.sources: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        if tag == "img":
            self.sources.extend(value or "" for name, value in attrs if name == "src")


def images_of(page: Path) -> list[str]:
    parser = _Images()
    parser.feed(page.read_text(encoding="utf-8"))
    return parser.sources


def test_python_code_is_shown_only_in_executed_notebooks():
    assert pages_with_unexecuted_python(DOCS) == []


def test_the_guide_and_the_tutorials_are_notebooks():
    documented = [name for name, text in pages(DOCS).items()
                  if name.startswith(("guide/", "tutorials/")) and CODE_CELL.search(text)]
    assert len(documented) >= 15


def test_the_build_executes_every_notebook_and_fails_on_an_error():
    conf = (DOCS / "conf.py").read_text(encoding="utf-8")
    assert re.search(r'^nb_execution_mode = "force"$', conf, re.M)
    assert re.search(r"^nb_execution_raise_on_error = True$", conf, re.M)


def test_every_tutorial_draws_a_figure():
    assert tutorials_without_a_figure(DOCS) == []


def test_the_checks_see_unexecuted_python_and_tutorials_without_figures(tmp_path):
    (tmp_path / "tutorials").mkdir()
    (tmp_path / "guide.md").write_text("# Guide\n\n```python\nprint(1)\n```\n")
    (tmp_path / "cells.md").write_text("# No kernel\n\n```{code-cell} ipython3\nprint(1)\n```\n")
    notebook = "---\nkernelspec:\n  name: python3\n---\n\n```{code-cell} ipython3\n"
    (tmp_path / "skipped.md").write_text(notebook + ":tags: [skip-execution]\n\nprint(1)\n```\n")
    (tmp_path / "own_fmu.md").write_text(
        notebook + ":tags: [skip-execution]\n\nFMUComponent('C', 'Clocks.fmu')\n```\n")
    (tmp_path / "tutorials" / "01.md").write_text(
        "---\nkernelspec:\n  name: python3\n---\n\n```{code-cell} ipython3\nprint(1)\n```\n")
    (tmp_path / "tutorials" / "02.md").write_text(
        "---\nkernelspec:\n  name: python3\n---\n\n```{code-cell} ipython3\n"
        "figure = result.plot(['P.theta'])\n```\n")
    assert pages_with_unexecuted_python(tmp_path) == ["cells.md", "guide.md", "skipped.md"]
    assert tutorials_without_a_figure(tmp_path) == ["01.md"]


@pytest.mark.skipif(not (BUILT_SITE / "index.html").is_file(),
                    reason="no built documentation (the test command builds it before pytest)")
def test_every_tutorial_of_the_built_site_shows_a_figure():
    tutorials = sorted((BUILT_SITE / "tutorials").glob("0*.html"))
    assert len(tutorials) >= 4
    without = [page.name for page in tutorials
               if not any(source.startswith("../_images/") for source in images_of(page))]
    assert without == []
