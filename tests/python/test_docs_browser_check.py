"""The browser check of the documentation (scripts/check-docs-browser.py) finds what a reader
would see broken: on a small site made here it reports a console error, an uncaught exception,
an image that does not load, a tutorial without a figure, maths loaded from another site, a
search that finds nothing; on the same pages mended, nothing. Needs Chromium (skipped
without)."""

from __future__ import annotations

import importlib.util
import shutil
import struct
import zlib
from pathlib import Path
from types import ModuleType

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "check-docs-browser.py"


def one_pixel_png() -> bytes:
    def chunk(kind: bytes, data: bytes) -> bytes:
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data)))

    header = struct.pack(">IIBBBBB", 1, 1, 8, 0, 0, 0, 0)  # 1x1, 8-bit greyscale
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header)
            + chunk(b"IDAT", zlib.compress(b"\x00\x80")) + chunk(b"IEND", b""))


def load_checker() -> ModuleType:
    spec = importlib.util.spec_from_file_location("check_docs_browser", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def page(body: str, script: str = "") -> str:
    return f"<!DOCTYPE html><html><head>{script}</head><body>{body}</body></html>"


def write_site(root: Path, broken: bool) -> None:
    (root / "tutorials").mkdir(parents=True)
    (root / "figure.png").write_bytes(one_pixel_png())
    image = "missing.png" if broken else "figure.png"
    console = "<script>console.error('broken page')</script>" if broken else ""
    throw = "<script>undefined_function()</script>" if broken else ""
    (root / "index.html").write_text(page(f'<img src="{image}">{console}{throw}'))
    figure = "" if broken else '<img src="../figure.png">'
    (root / "tutorials" / "index.html").write_text(page("tutorials"))
    (root / "tutorials" / "first.html").write_text(page(f"<p>a tutorial</p>{figure}"))
    # maths: typeset by a script of the site, or asked of another site
    mathjax = ('<script src="https://cdn.example.invalid/mathjax.js"></script>' if broken else
               "<script src='_static/mathjax/fake.js'></script>")
    (root / "_static" / "mathjax").mkdir(parents=True)
    (root / "_static" / "mathjax" / "fake.js").write_text(
        "document.addEventListener('DOMContentLoaded', () => document.querySelectorAll"
        "('.math').forEach(m => m.classList.add('MathJax_CHTML')))")
    (root / "maths.html").write_text(page('<span class="math">\\(x^2\\)</span>', mathjax))
    found = "" if broken else "<li>stream_to</li>"
    (root / "search.html").write_text(page(f'<ul id="search-results">{found}</ul>'))


@pytest.mark.parametrize("broken", [True, False], ids=["broken", "mended"])
def test_the_check_reports_what_a_reader_sees_broken(tmp_path: Path, broken: bool,
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    checker = load_checker()
    # what the broken site never shows is waited for briefly
    monkeypatch.setattr(checker, "MATH_TIMEOUT", 2.0)
    monkeypatch.setattr(checker, "SEARCH_TIMEOUT", 2.0)
    executable = next((found for name in checker.BROWSERS if (found := shutil.which(name))),
                      None)
    if executable is None:
        pytest.skip("no Chromium")
    write_site(tmp_path, broken)
    server = checker.serve(tmp_path)
    browser = checker.Browser(executable)
    try:
        failures = checker.check_site(tmp_path, browser,
                                      f"http://127.0.0.1:{server.server_port}")
    finally:
        browser.close()
        server.shutdown()
    if not broken:
        assert failures == []
        return
    text = "\n".join(failures)
    assert "index.html: console: broken page" in text
    assert "index.html: exception: ReferenceError: undefined_function is not defined" in text
    assert "index.html: image not loaded: " in text and "missing.png" in text
    assert "tutorials/first.html: a tutorial without a figure" in text
    assert "tutorials/index.html" not in text
    assert "maths.html: MathJax comes from another site" in text
    assert "maths.html: its maths is not typeset" in text
    assert "search.html: searching 'stream_to' finds nothing" in text
