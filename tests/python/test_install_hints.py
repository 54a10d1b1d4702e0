"""Install hints name the distribution syssimx-engine: `syssimx` on PyPI is SysSimX, another
project, so a hint naming it would replace this package with that one."""

from __future__ import annotations

import ast
import re
from pathlib import Path

from syssimx.extras import EXTRAS, install_hint

ROOT = Path(__file__).resolve().parents[2]

# `pip install` (options allowed) of the bare name syssimx, with or without extras; a path
# ending in syssimx (./syssimx, path/to/syssimx[ensemble]) or syssimx-engine is not matched
WRONG_INSTALL = re.compile(r"""pip3?\s+install\s+(?:-[\w-]+\s+)*["']?syssimx(?![\w./-])""")


def _python_strings(path: Path) -> list[str]:
    """Every string literal of a module: adjacent literals are joined by the parser, so a hint
    split over two source lines is read whole."""
    return [node.value for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
            if isinstance(node, ast.Constant) and isinstance(node.value, str)]


def _texts() -> dict[str, list[str]]:
    texts = {str(path.relative_to(ROOT)): _python_strings(path)
             for path in sorted((ROOT / "python" / "syssimx").rglob("*.py"))}
    documents = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    texts.update({str(path.relative_to(ROOT)): [path.read_text(encoding="utf-8")]
                  for path in documents})
    return texts


def test_the_pattern_tells_the_wrong_name_from_the_right_one():
    for wrong in ('pip install "syssimx[results]"', "pip install syssimx",
                  "pip install -U syssimx", "pip install 'syssimx[viz]'"):
        assert WRONG_INSTALL.search(wrong), wrong
    for right in ('pip install "syssimx-engine[results]"', "pip install ./syssimx",
                  'pip install "path/to/syssimx[ensemble]"', "pip install syssimx_engine-0.5.whl"):
        assert not WRONG_INSTALL.search(right), right


def test_no_package_readme_or_docs_text_installs_the_other_project():
    texts = _texts()
    assert "python/syssimx/extras.py" in texts and "docs/guide/results.md" in texts
    offenders = [f"{name}: {match.group(0)!r}" for name, strings in texts.items()
                 for text in strings for match in WRONG_INSTALL.finditer(text)]
    assert offenders == []


def test_every_extra_hint_names_syssimx_engine():
    for library, extra in EXTRAS.items():
        assert install_hint(library) == f'pip install "syssimx-engine[{extra}]"'
