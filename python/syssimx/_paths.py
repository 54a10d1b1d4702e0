"""Where the compiled parts of syssimx live: the engine library, its header, the FMU host
executable and the FMUs.

An installed package carries them inside its own directory. During development, setting
SYSSIMX_BUILD_DIR to a meson build directory of this repository uses that build instead.
"""

from __future__ import annotations

import os
from pathlib import Path

_PACKAGE_DIR = Path(__file__).resolve().parent
_SOURCE_ROOT = _PACKAGE_DIR.parent.parent

ENGINE_LIBRARY = "libsyssimx_engine.so"
ENGINE_HEADER = "syssimx_engine.h"
FMU_HOST = "syssimx-fmu-host"


# A relative SYSSIMX_BUILD_DIR means relative to where syssimx was imported, whatever the
# current directory is later.
_IMPORT_DIR = Path.cwd()


def build_dir() -> Path | None:
    """The meson build directory named by SYSSIMX_BUILD_DIR, if any."""
    value = os.environ.get("SYSSIMX_BUILD_DIR")
    return (_IMPORT_DIR / value).resolve() if value else None


def engine_library() -> Path:
    build = build_dir()
    candidate = build / "src" / ENGINE_LIBRARY if build else _PACKAGE_DIR / ENGINE_LIBRARY
    if not candidate.is_file():
        raise FileNotFoundError(
            f"the syssimx engine library was not found at {candidate}; "
            "build the package (pip install .) or point SYSSIMX_BUILD_DIR at a meson build"
        )
    return candidate


def fmu_host() -> Path:
    """The executable an isolated FMU runs in, installed beside the engine library."""
    build = build_dir()
    candidate = build / "src" / FMU_HOST if build else _PACKAGE_DIR / FMU_HOST
    if not candidate.is_file():
        raise FileNotFoundError(
            f"the syssimx FMU host {candidate} was not found; build the package (pip install .) "
            "or point SYSSIMX_BUILD_DIR at a meson build"
        )
    return candidate


def engine_header() -> Path:
    for candidate in (_PACKAGE_DIR / ENGINE_HEADER, _SOURCE_ROOT / "src" / ENGINE_HEADER):
        if candidate.is_file():
            return candidate
    raise FileNotFoundError(f"the engine header {ENGINE_HEADER} was not found")


def fmu_dir() -> Path:
    build = build_dir()
    return build / "models" if build else _PACKAGE_DIR / "fmus"
