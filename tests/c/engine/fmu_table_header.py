"""Write a C header listing each built FMU's binary and GUID (FMI 3.0: instantiation token), for
the engine's C tests.

Usage: fmu_table_header.py <output.h> (<stem> <file.fmu> <binary.so>)...
"""

from __future__ import annotations

import re
import sys
import zipfile


def guid_of(fmu: str) -> str:
    with zipfile.ZipFile(fmu) as archive:
        description = archive.read("modelDescription.xml").decode("utf-8")
    # FMI 3.0 names the GUID instantiationToken
    match = re.search(r'\b(?:guid|instantiationToken)="([^"]+)"', description)
    if match is None:
        raise SystemExit(f"{fmu}: modelDescription.xml has no guid or instantiationToken")
    return match.group(1)


def main(argv: list[str]) -> int:
    if len(argv) < 2 or (len(argv) - 2) % 3 != 0:
        print(__doc__, file=sys.stderr)
        return 2
    lines = [
        "/* Generated at build time: the FMUs built alongside the engine, as initializers",
        " * {stem, binary, guid}. */",
        "#pragma once",
        "#define ENGINE_TEST_FMUS \\",
    ]
    entries = argv[2:]
    for stem, fmu, binary in zip(entries[0::3], entries[1::3], entries[2::3], strict=True):
        lines.append(f'    {{"{stem}", "{binary}", "{guid_of(fmu)}"}}, \\')
    lines.append("")
    with open(argv[1], "w", encoding="utf-8") as out:
        out.write("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
