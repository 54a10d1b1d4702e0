"""Where the users' system files are (SSP and OSP files as OMSimulator and libcosim wrote
them): SYSSIMX_SSP_SAMPLES, else <repository>/../shared/ssp-samples; tests skip without them."""

from __future__ import annotations

import os
from pathlib import Path

import pytest


def samples_root() -> Path:
    given = os.environ.get("SYSSIMX_SSP_SAMPLES")
    root = Path(given) if given else \
        Path(__file__).resolve().parents[2].parent / "shared" / "ssp-samples"
    if not root.is_dir():
        pytest.skip(f"the users' SSP/OSP samples are absent (no {root}): set SYSSIMX_SSP_SAMPLES")
    return root.resolve()
