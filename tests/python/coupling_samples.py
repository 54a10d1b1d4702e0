"""Where the users' coupled systems are (libcosim's quarter truck, ...): SYSSIMX_COUPLING_SAMPLES,
else <repository>/../shared/coupling-samples."""

from __future__ import annotations

import os
from pathlib import Path


def coupling_samples_root() -> Path:
    given = os.environ.get("SYSSIMX_COUPLING_SAMPLES")
    if given:
        return Path(given).resolve()
    return (Path(__file__).resolve().parents[2].parent / "shared" /
            "coupling-samples").resolve()
