"""Where the compiled parts of syssimx live: the engine library, its header and cffi module, the
FMU host executable and the FMUs.

An installed package carries them inside its own directory. During development, setting
SYSSIMX_BUILD_DIR to a meson build directory of this repository uses that build instead.
"""

from __future__ import annotations

import functools
import json
import os
from pathlib import Path

_PACKAGE_DIR = Path(__file__).resolve().parent
_SOURCE_ROOT = _PACKAGE_DIR.parent.parent

ENGINE_LIBRARY = "libsyssimx_engine.so"
ENGINE_HEADER = "syssimx_engine.h"
ENGINE_FFI_MODULE = "_engine_ffi.py"
FMU_HOST = "syssimx-fmu-host"
EXPORT_BINARY = "libsyssimx_fmu.so"


# A relative SYSSIMX_BUILD_DIR means relative to where syssimx was imported, whatever the
# current directory is later.
_IMPORT_DIR = Path.cwd()


def build_dir() -> Path | None:
    """The meson build directory named by SYSSIMX_BUILD_DIR, if any."""
    value = os.environ.get("SYSSIMX_BUILD_DIR")
    return (_IMPORT_DIR / value).resolve() if value else None


def _built(name: str, what: str, folder: str = "src") -> Path:
    """A file the meson build makes in `folder` and installs beside this package's modules."""
    build = build_dir()
    candidate = build / folder / name if build else _PACKAGE_DIR / name
    if not candidate.is_file():
        raise FileNotFoundError(
            f"{what} was not found at {candidate}; build the package (pip install .) or point "
            "SYSSIMX_BUILD_DIR at a meson build"
        )
    return candidate


def engine_library() -> Path:
    return _built(ENGINE_LIBRARY, "the syssimx engine library")


def engine_ffi_module() -> Path:
    """The cffi module the build generates from the engine header (out-of-line ABI mode)."""
    return _built(ENGINE_FFI_MODULE, "the syssimx engine's cffi module")


def fmu_host() -> Path:
    """The executable an isolated FMU runs in, installed beside the engine library."""
    return _built(FMU_HOST, "the syssimx FMU host")


def export_binary() -> Path:
    """The binary of an exported system's FMU: the engine under FMI entry points."""
    return _built(EXPORT_BINARY, "the exported FMU's binary", "src/export")


def engine_header() -> Path:
    source_header = _SOURCE_ROOT / "src" / "include" / ENGINE_HEADER
    for candidate in (_PACKAGE_DIR / ENGINE_HEADER, source_header):
        if candidate.is_file():
            return candidate
    raise FileNotFoundError(f"the engine header {ENGINE_HEADER} was not found")


def installed_from_build() -> frozenset[str] | None:
    """The files a meson build (SYSSIMX_BUILD_DIR) installs, by their path in the build; None
    for an installed package or a build without meson's introspection data."""
    build = build_dir()
    listing = build / "meson-info" / "intro-installed.json" if build else None
    if listing is None or not listing.is_file():
        return None
    return _installed_listing(str(listing), listing.stat().st_mtime_ns)


@functools.lru_cache(maxsize=4)
def _installed_listing(listing: str, modified_ns: int) -> frozenset[str]:
    """The files a build's listing names, read again only when the listing changes."""
    del modified_ns  # part of the cache key only
    return frozenset(str(Path(built).resolve()) for built in json.loads(Path(listing).read_text()))


def fmu_dir() -> Path:
    build = build_dir()
    return build / "models" if build else _PACKAGE_DIR / "fmus"
