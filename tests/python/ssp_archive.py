"""Writing SSP archives in tests: SSD text, parameter files and bundled FMUs zipped together."""

from __future__ import annotations

import zipfile
from pathlib import Path

from syssimx import fmus

SSD_NAMESPACES = (
    'xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription" '
    'xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon" '
    'xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues" '
    'xmlns:ssm="http://ssp-standard.org/SSP1/SystemStructureParameterMapping" '
    'xmlns:ssb="http://ssp-standard.org/SSP1/SystemStructureSignalDictionary"'
)


def ssd(system: str, name: str = "test", experiment: str = "", units: str = "") -> str:
    """A SystemStructure.ssd around the <ssd:System> text `system`."""
    return (f'<?xml version="1.0" encoding="UTF-8"?>\n<ssd:SystemStructureDescription '
            f'{SSD_NAMESPACES} version="1.0" name="{name}">\n{system}\n{units}\n{experiment}\n'
            '</ssd:SystemStructureDescription>\n')


def write_ssp(path: Path, ssd_text: str, files: dict[str, str] | None = None,
              bundled: tuple[str, ...] = ()) -> Path:
    """An .ssp at `path`: the SSD, the text `files` by archive name and bundled FMUs as
    resources/<name>.fmu."""
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("SystemStructure.ssd", ssd_text)
        for name, text in (files or {}).items():
            archive.writestr(name, text)
        for name in bundled:
            archive.write(fmus.path(name), f"resources/{name}.fmu")
    return path


def reference_fmu(name: str) -> Path:
    """A Reference FMU (FMI 2.0) from SYSSIMX_REFERENCE_FMUS or <repository>/../shared; the
    test is skipped when they are absent."""
    import os

    import pytest

    root = Path(os.environ.get("SYSSIMX_REFERENCE_FMUS",
                               Path(__file__).resolve().parents[3] / "shared" / "reference-fmus"))
    path = root / "fmi2" / f"{name}.fmu"
    if not path.is_file():
        pytest.skip(f"the Reference FMUs are absent (no {path}): set SYSSIMX_REFERENCE_FMUS")
    return path
