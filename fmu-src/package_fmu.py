"""Package an FMU: zip the modelDescription.xml written by the model's describe tool with the
model's shared library.

Usage: package_fmu.py <modelDescription.xml> <shared library> <modelIdentifier> <output.fmu>
"""

from __future__ import annotations

import sys
import zipfile
from pathlib import Path


def package(description: Path, binary: Path, model_identifier: str, output: Path) -> None:
    partial = output.with_suffix(".fmu.partial")
    with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.write(description, "modelDescription.xml")
        archive.write(binary, f"binaries/linux64/{model_identifier}.so")
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
