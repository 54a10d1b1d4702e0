"""Package an FMU: zip the modelDescription.xml written by the model's describe tool with the
model's shared library, in the platform folder of the description's FMI version.

Usage: package_fmu.py <modelDescription.xml> <shared library> <modelIdentifier> <output.fmu>
"""

from __future__ import annotations

import sys
import xml.etree.ElementTree as ElementTree
import zipfile
from pathlib import Path

# FMI 1.0 and 2.0 name the platform "linux64", FMI 3.0 by its platform tuple
PLATFORM_FOLDERS = {"1.0": "linux64", "2.0": "linux64", "3.0": "x86_64-linux"}


def package(description: Path, binary: Path, model_identifier: str, output: Path) -> None:
    version = ElementTree.parse(description).getroot().get("fmiVersion")
    platform = PLATFORM_FOLDERS[version]
    partial = output.with_suffix(".fmu.partial")
    with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.write(description, "modelDescription.xml")
        archive.write(binary, f"binaries/{platform}/{model_identifier}.so")
    partial.replace(output)


def main(argv: list[str]) -> int:
    if len(argv) != 5:
        print(__doc__, file=sys.stderr)
        return 2
    description, binary, model_identifier, output = argv[1:]
    package(Path(description), Path(binary), model_identifier, Path(output))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
