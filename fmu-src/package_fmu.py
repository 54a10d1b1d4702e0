"""Package an FMU: run the model's describe tool and zip its XML with the shared library.

Usage: package_fmu.py <describe executable> <shared library> <modelIdentifier> <output.fmu>
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path


def package(describe: Path, binary: Path, model_identifier: str, output: Path) -> None:
    with tempfile.TemporaryDirectory() as scratch:
        description = Path(scratch) / "modelDescription.xml"
        subprocess.run([str(describe), model_identifier, str(description)], check=True)
        partial = output.with_suffix(".fmu.partial")
        with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as archive:
            archive.write(description, "modelDescription.xml")
            archive.write(binary, f"binaries/linux64/{model_identifier}.so")
        partial.replace(output)


def main(argv: list[str]) -> int:
    if len(argv) != 5:
        print(__doc__, file=sys.stderr)
        return 2
    describe, binary, model_identifier, output = argv[1:]
    package(Path(describe), Path(binary), model_identifier, Path(output))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
