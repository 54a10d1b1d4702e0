"""The version is written once (meson.build) and every place that shows it agrees: the package,
`syssimx --version`, the installed distribution's metadata and the CHANGELOG."""

from __future__ import annotations

import importlib
import re
import tomllib
from importlib.metadata import distribution
from pathlib import Path

import pytest
import syssimx
from syssimx._version import DISTRIBUTION

ROOT = Path(__file__).resolve().parents[2]


def meson_version() -> str:
    meson_build = (ROOT / "meson.build").read_text()
    found = re.search(r"project\('syssimx'.*?version: '([^']+)'", meson_build, re.S)
    assert found, "meson.build declares no project version"
    return found.group(1)


def test_the_package_version_is_meson_builds():
    assert syssimx.__version__ == meson_version()
    assert syssimx.__version_info__ == tuple(int(p) for p in meson_version().split("."))


def test_pyproject_takes_the_version_from_meson_and_names_our_own_distribution():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert "version" not in project
    assert project["dynamic"] == ["version"]
    assert project["name"] == DISTRIBUTION
    # "syssimx" on PyPI is SysSimX; normalized names must differ
    assert re.sub(r"[-_.]+", "-", project["name"]).lower() != "syssimx"


def test_the_command_line_prints_the_version(capsys):
    # the function the `syssimx` script runs, as pyproject declares it
    target = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"]["syssimx"]
    module, function = target.split(":")
    assert getattr(importlib.import_module(module), function)(["--version"]) == 0
    assert capsys.readouterr().out == f"syssimx {meson_version()}\n"


def test_an_installed_package_carries_the_same_version_in_its_metadata():
    package = Path(syssimx.__file__).resolve().parent
    # the project's .venv lies inside the checkout too: only python/ is the source tree
    if package == ROOT / "python" / "syssimx":
        pytest.skip("syssimx is imported from the source tree: no distribution metadata")
    installed = distribution(DISTRIBUTION)
    assert Path(str(installed.locate_file("syssimx/__init__.py"))).resolve().parent == package
    assert installed.version == meson_version()
    assert installed.metadata["License-Expression"] == "MIT"


def test_the_changelog_describes_this_version_and_the_license_is_mit():
    changelog = (ROOT / "CHANGELOG.md").read_text()
    assert re.search(rf"^## \[?{re.escape(meson_version())}\]?", changelog, re.M)
    license_text = (ROOT / "LICENSE").read_text()
    assert license_text.startswith("MIT License") and "the syssimx developers" in license_text
