"""Every Python example of the documentation's Markdown pages runs as printed: the ```python
blocks of a page, top to bottom in one namespace, in a temporary folder, as a script runs
(`__name__ == "__main__"`). Notebook pages (a `kernelspec` in their front matter) are executed
by the documentation build instead."""

from __future__ import annotations

import re
from pathlib import Path

import matplotlib
import pytest

DOCS = Path(__file__).resolve().parents[2] / "docs"
PYTHON_BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


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


def test_the_documentation_has_python_examples_outside_the_notebooks():
    assert len(pages_with_examples()) >= 3


@pytest.mark.parametrize("page", pages_with_examples(),
                         ids=lambda page: str(page.relative_to(DOCS)))
def test_the_examples_of_a_page_run(page: Path, tmp_path, monkeypatch):
    matplotlib.use("Agg")  # figures are drawn, never shown
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, object] = {"__name__": "__main__"}
    text = page.read_text(encoding="utf-8")
    for match in PYTHON_BLOCK.finditer(text):
        line = text.count("\n", 0, match.start(1)) + 1
        # a traceback names the page and its line
        code = compile("\n" * (line - 1) + match.group(1), str(page), "exec")
        exec(code, namespace)
