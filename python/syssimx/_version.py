"""The version of syssimx, written once: meson.build's `project(version:)`.

meson-python copies it into the installed distribution's metadata, which is read here. A source
tree run without installing (PYTHONPATH and SYSSIMX_BUILD_DIR) has no metadata of its own, so the
version is read from its meson.build.
"""

from __future__ import annotations

import re
from pathlib import Path

DISTRIBUTION = "syssimx-engine"

_PACKAGE_DIR = Path(__file__).resolve().parent
_PROJECT_VERSION = re.compile(r"project\(\s*'syssimx'.*?\bversion\s*:\s*'([^']+)'", re.S)


def _installed_version() -> str | None:
    """The metadata version of the installed distribution, if this package is the one it holds
    (not a source tree imported beside another installed copy)."""
    from importlib.metadata import PackageNotFoundError, distribution

    try:
        installed = distribution(DISTRIBUTION)
    except PackageNotFoundError:
        return None
    init = Path(str(installed.locate_file("syssimx/__init__.py")))
    return installed.version if init.resolve() == _PACKAGE_DIR / "__init__.py" else None


def _source_tree_version() -> str:
    meson_build = _PACKAGE_DIR.parent.parent / "meson.build"
    if not meson_build.is_file():
        raise RuntimeError(f"syssimx at {_PACKAGE_DIR} is neither installed as "
                           f"{DISTRIBUTION!r} nor inside its source tree (no {meson_build})")
    found = _PROJECT_VERSION.search(meson_build.read_text(encoding="utf-8"))
    if found is None:
        raise RuntimeError(f"{meson_build} declares no project version")
    return found.group(1)


__version__ = _installed_version() or _source_tree_version()
__version_info__ = tuple(int(part) for part in __version__.split("."))
