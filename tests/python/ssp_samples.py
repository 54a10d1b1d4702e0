"""The users' system files (SSP and OSP files as OMSimulator and libcosim wrote them) for
tests, which skip without them, and a copy of libcosim's crane structure for comparisons."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest
from samples_root import samples_root


def available_samples() -> Path:
    """The samples folder (samples_root.py says where); the test is skipped without it."""
    root = samples_root()
    if not root.is_dir():
        pytest.skip(f"the users' SSP/OSP samples are absent (no {root}): set SYSSIMX_SSP_SAMPLES")
    return root


def crane_without_step_sizes(root: Path, folder: Path) -> Path:
    """A copy of libcosim's OspSystemStructure_Bond.xml in `folder` without the simulators'
    own stepSize (libcosim's multi-rate stepping, which syssimx does not do), beside copies
    of its FMUs and OSP model descriptions where libcosim's test data has them."""
    source = root / "libcosim"
    for kind in ("fmi1", "fmi2"):
        shutil.copytree(source / kind, folder / kind)
    (folder / "msmi").mkdir()
    shutil.copy(source / "msmi" / "CraneController_OspModelDescription.xml", folder / "msmi")
    text = (source / "msmi" / "OspSystemStructure_Bond.xml").read_text()
    path = folder / "msmi" / "OspSystemStructure_Bond.xml"
    path.write_text(re.sub(r' stepSize="[^"]*"', "", text))
    return path
