"""Where the Reference FMUs are: SYSSIMX_REFERENCE_FMUS, else <repository>/../shared."""

from __future__ import annotations

import os
from pathlib import Path


def reference_root() -> Path:
    """The folder holding fmi2/ and fmi3/, resolved as the FMU files are: messages name an FMU
    by its resolved path."""
    given = os.environ.get("SYSSIMX_REFERENCE_FMUS")
    if given:
        return Path(given).resolve()
    return (Path(__file__).resolve().parents[2].parent / "shared" / "reference-fmus").resolve()
