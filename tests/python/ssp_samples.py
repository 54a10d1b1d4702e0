"""Where the users' system files are (SSP and OSP files as OMSimulator and libcosim wrote
them): SYSSIMX_SSP_SAMPLES, else <repository>/../shared/ssp-samples; tests skip without them."""

from __future__ import annotations

import os
import re
import shutil
import zipfile
from pathlib import Path

import pytest


def samples_root() -> Path:
    given = os.environ.get("SYSSIMX_SSP_SAMPLES")
    root = Path(given) if given else \
        Path(__file__).resolve().parents[2].parent / "shared" / "ssp-samples"
    if not root.is_dir():
        pytest.skip(f"the users' SSP/OSP samples are absent (no {root}): set SYSSIMX_SSP_SAMPLES")
    return root.resolve()


def utf8_crane(root: Path, folder: Path, step_sizes: bool = True) -> Path:
    """A copy of libcosim's OspSystemStructure_Bond.xml in `folder` without the FMI 1.0
    identity simulators (and without the simulators' own stepSize unless `step_sizes`),
    beside copies of the crane FMUs whose modelDescription declares UTF-8 (it is ASCII;
    20-sim declares ISO-8859-1), with the OSP model descriptions where libcosim's test data
    has them: the controller's beside the structure, the crane's beside its FMU."""
    source = root / "libcosim"
    (folder / "msmi").mkdir(parents=True)
    (folder / "fmi2").mkdir()
    for name in ("CraneController", "KnuckleBoomCrane"):
        with zipfile.ZipFile(source / "fmi2" / f"{name}.fmu") as original, \
                zipfile.ZipFile(folder / "fmi2" / f"{name}.fmu", "w") as copy:
            for entry in original.infolist():
                data = original.read(entry)
                if entry.filename == "modelDescription.xml":
                    data = data.replace(b'encoding="ISO-8859-1"', b'encoding="UTF-8"', 1)
                copy.writestr(entry, data)
    shutil.copy(source / "fmi2" / "KnuckleBoomCrane_OspModelDescription.xml", folder / "fmi2")
    shutil.copy(source / "msmi" / "CraneController_OspModelDescription.xml", folder / "msmi")
    text = (source / "msmi" / "OspSystemStructure_Bond.xml").read_text()
    text = re.sub(r'<Simulator name="(True|One)Identity".*?</Simulator>', "", text,
                  flags=re.DOTALL)
    if not step_sizes:
        text = re.sub(r' stepSize="[^"]*"', "", text)
    path = folder / "msmi" / "OspSystemStructure_Bond.xml"
    path.write_text(text)
    return path
