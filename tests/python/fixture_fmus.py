"""The FMUs the tests use: the bundled ones (syssimx.fmus), and the test fixtures built from
tests/fmus, which are never installed. The fixtures are found in SYSSIMX_FIXTURE_FMUS, else in
the meson build SYSSIMX_BUILD_DIR points at, else in the build the install script keeps
(build/release)."""

from __future__ import annotations

import os
import re
from pathlib import Path

from syssimx import fmus

ROOT = Path(__file__).resolve().parents[2]

# the fixtures' stems, read from the one list of them (tests/fmus/meson.build)
FIXTURES = re.findall(r"^\s*\['(\w+)',", (ROOT / "tests" / "fmus" / "meson.build").read_text(),
                      re.M)


def fixture_dir() -> Path:
    given = os.environ.get("SYSSIMX_FIXTURE_FMUS")
    if given:
        return Path(given).resolve()
    build = os.environ.get("SYSSIMX_BUILD_DIR")
    return (Path(build).resolve() if build else ROOT / "build" / "release") / "models"


def fmu_path(name: str) -> str:
    """The path of a test fixture (e.g. "failing", "terminating_fmi3", "hostile_ball_fmi1_me")
    or a bundled FMU."""
    if re.sub(r"_fmi(3|1|1_me)$", "", name) not in FIXTURES:
        return fmus.path(name)
    path = fixture_dir() / f"{name}.fmu"
    if not path.is_file():
        raise FileNotFoundError(f"the test fixture {name}.fmu is not in {path.parent}: build "
                                "with meson and set SYSSIMX_BUILD_DIR (or SYSSIMX_FIXTURE_FMUS)")
    return str(path)
