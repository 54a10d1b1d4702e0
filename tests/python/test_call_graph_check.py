"""The engine's call-graph check (tests/c/layout/call_graph.py, run by `meson test`) fails on
a circle of calls between object files and names the symbols that close it, and passes calls
that go one way."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

CHECK = Path(__file__).resolve().parents[1] / "c" / "layout" / "call_graph.py"
COMPILER = shutil.which("cc") or shutil.which("gcc")

pytestmark = pytest.mark.skipif(
    COMPILER is None or shutil.which("nm") is None, reason="needs a C compiler and nm")


def _objects(folder: Path, sources: dict[str, str]) -> None:
    """Compiles each source into folder as meson names an object of src/fmu/ (fmu_x.c.o)."""
    for stem, code in sources.items():
        source = folder / f"{stem}.c"
        source.write_text(code)
        subprocess.run([str(COMPILER), "-c", str(source), "-o", str(folder / f"{stem}.c.o")],
                       check=True)


def _check(folder: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, str(CHECK), "nm", "fmu_", str(folder)],
                          capture_output=True, text=True)


def test_a_circle_of_calls_fails_and_names_its_symbols(tmp_path: Path) -> None:
    _objects(tmp_path, {
        "fmu_binding": "void backend_step(void); void binding_log(void) {}\n"
                       "void binding_step(void) { backend_step(); }\n",
        "fmu_backend": "void binding_log(void); void backend_step(void) { binding_log(); }\n",
    })
    result = _check(tmp_path)
    assert result.returncode == 1
    assert "circle: fmu_backend, fmu_binding" in result.stdout
    assert "fmu_backend calls fmu_binding: binding_log" in result.stdout


def test_calls_one_way_pass(tmp_path: Path) -> None:
    _objects(tmp_path, {
        "fmu_binding": "void backend_step(void); void message(void);\n"
                       "void binding_step(void) { backend_step(); message(); }\n",
        "fmu_backend": "void message(void); void backend_step(void) { message(); }\n",
        "fmu_message": "void message(void) {}\n",
    })
    result = _check(tmp_path)
    assert result.returncode == 0, result.stdout
    assert "3 files, 0 circles" in result.stdout
