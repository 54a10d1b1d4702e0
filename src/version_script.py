"""Writes the engine's linker version script: the functions declared in the public header are
exported, every other symbol stays inside the library.

Usage: version_script.py syssimx_engine.h OUTPUT
"""

import re
import sys

# a declaration's name: `ssx_name(` at the start of a line or after the return type
DECLARED = re.compile(r"\b(ssx_\w+)\s*\(")


def declarations(header: str) -> str:
    """The header without its preprocessor lines: the plain C that cffi parses."""
    with open(header, encoding="utf-8") as source:
        return "\n".join(line.rstrip("\n") for line in source
                         if not line.lstrip().startswith("#"))


def main(header: str, output: str) -> None:
    # comments name functions too
    text = re.sub(r"/\*.*?\*/", "", declarations(header), flags=re.DOTALL)
    names = sorted(set(DECLARED.findall(text)))
    with open(output, "w", encoding="utf-8") as script:
        script.write("{\n  global:\n")
        script.writelines(f"    {name};\n" for name in names)
        script.write("  local: *;\n};\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
