"""Where the users' system files and third-party FMUs are: SYSSIMX_SSP_SAMPLES, else
<repository>/../shared/ssp-samples."""

from __future__ import annotations

import os
from pathlib import Path


def samples_root() -> Path:
    given = os.environ.get("SYSSIMX_SSP_SAMPLES")
    if given:
        return Path(given).resolve()
    return (Path(__file__).resolve().parents[2].parent / "shared" / "ssp-samples").resolve()
