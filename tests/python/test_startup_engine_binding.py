"""The engine binding is the cffi module the build generated from the header (out-of-line ABI
mode): importing and running syssimx parses no C, and a library built from another header than
the module is refused with a message that says so."""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
from pathlib import Path

from syssimx import _paths, engine

ROOT = Path(__file__).resolve().parents[2]


def python(code: str, **environment: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-c", code], env={**os.environ, **environment},
                          capture_output=True, text=True)


def test_a_run_parses_no_c():
    code = ("import sys\nfrom syssimx import FMUComponent, System, fmus\n"
            "system = System('s')\nsystem.add_component(FMUComponent('G', fmus.path('gain')))\n"
            "system.initialize(0.0)\nsystem.run(0.0, 1.0, 0.5)\n"
            "print(sorted(m for m in ('pycparser', 'cffi.cparser') if m in sys.modules))")
    finished = python(code)
    assert finished.returncode == 0, finished.stderr
    assert finished.stdout.splitlines()[-1] == "[]"


def test_the_library_holds_the_digest_of_the_header_its_module_was_made_from():
    header = hashlib.sha256(_paths.engine_header().read_bytes()).hexdigest()
    built = engine.ffi.string(engine.lib().ssx_interface_digest()).decode()
    assert built == header


def test_a_library_built_from_another_header_than_its_module_is_refused(tmp_path: Path):
    stale = tmp_path / "build" / "src"
    stale.mkdir(parents=True)
    library = shutil.copy(_paths.engine_library(), stale)
    # the module of a header that gained a declaration since the library was built
    header = tmp_path / _paths.ENGINE_HEADER
    header.write_text(_paths.engine_header().read_text() + "int ssx_declared_later(void);\n")
    module = stale / _paths.ENGINE_FFI_MODULE
    subprocess.run([sys.executable, ROOT / "src" / "engine_ffi.py", header, module,
                    tmp_path / "engine_interface.c"], check=True, capture_output=True)
    finished = python("from syssimx.engine import lib\nlib()",
                      SYSSIMX_BUILD_DIR=str(tmp_path / "build"))
    built = engine.ffi.string(engine.lib().ssx_interface_digest()).decode()
    generated = hashlib.sha256(header.read_bytes()).hexdigest()
    assert finished.returncode == 1
    assert finished.stderr.splitlines()[-1] == (
        f"syssimx.errors.EngineMismatchError: the engine library {library} was built from "
        f"another syssimx_engine.h than its cffi module {module} (header digest {built} against "
        f"{generated}): a stale build; rebuild both (meson compile, or pip install .)")


def test_a_build_without_the_module_names_it(tmp_path: Path):
    finished = python("import syssimx.engine", SYSSIMX_BUILD_DIR=str(tmp_path))
    assert finished.returncode == 1
    assert finished.stderr.splitlines()[-1] == (
        f"FileNotFoundError: the syssimx engine's cffi module was not found at "
        f"{tmp_path / 'src' / '_engine_ffi.py'}; build the package (pip install .) or point "
        "SYSSIMX_BUILD_DIR at a meson build")
