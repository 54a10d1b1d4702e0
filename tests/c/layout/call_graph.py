"""Checks that the engine's object files call one another without a circle.

File A needs file B when A's object uses a symbol (a function or a table) that B's object
defines, as `nm` lists them. No file of the rooms checked may need a file that needs it back:
a circle is printed with the symbols that close it, and the check fails. An interface with its
implementations is no circle here: the binding names each back-end's table, and a back-end
needs only the neutral helpers beside the binding, never the binding.

Usage: call_graph.py NM ROOM_PREFIX,... OBJECT_DIR...
(ROOM_PREFIX: the start of an object's name as meson writes it, "fmu_" for src/fmu/...;
OBJECT_DIR: a folder of one binary's object files, each binary checked on its own)
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from include_graph import circles

DEFINED = frozenset("TDRBCGSV")


def symbols(nm: str, obj: Path) -> tuple[set[str], set[str]]:
    """The external symbols the object defines, and those it uses."""
    listing = subprocess.run([nm, "-g", str(obj)], capture_output=True, text=True, check=True)
    defined: set[str] = set()
    used: set[str] = set()
    for line in listing.stdout.splitlines():
        fields = line.split()
        if len(fields) == 2 and fields[0] == "U":
            used.add(fields[1])
        elif len(fields) == 3 and fields[1] in DEFINED:
            defined.add(fields[2])
    return defined, used


def file_name(obj: Path) -> str:
    """src/fmu/fmu_binding.c's object fmu_fmu_binding.c.o -> fmu_fmu_binding."""
    return obj.name.removesuffix(".o").removesuffix(".c")


def check(nm: str, objects: list[Path]) -> int:
    """Prints the circles among the objects' files; returns how many."""
    owner: dict[str, str] = {}
    uses: dict[str, set[str]] = {}
    for obj in objects:
        defined, used = symbols(nm, obj)
        name = file_name(obj)
        owner.update(dict.fromkeys(defined, name))
        uses[name] = used
    needs: dict[str, set[str]] = {name: set() for name in uses}
    through: dict[tuple[str, str], list[str]] = {}
    for name, used in uses.items():
        for symbol in sorted(used):
            other = owner.get(symbol)
            if other is not None and other != name:
                needs[name].add(other)
                through.setdefault((name, other), []).append(symbol)
    found = circles(needs)
    for group in found:
        members = set(group)
        print("circle: " + ", ".join(group))
        for name in group:
            for other in sorted(needs[name] & members):
                print(f"  {name} calls {other}: {', '.join(through[(name, other)])}")
    print(f"{objects[0].parent.name}: {len(needs)} files, {len(found)} circles")
    return len(found)


def main(argv: list[str]) -> int:
    if len(argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    nm, prefixes = argv[1], tuple(argv[2].split(","))
    found = 0
    for folder in argv[3:]:
        objects = sorted(
            p for p in Path(folder).glob("*.o") if file_name(p).startswith(prefixes)
        )
        if not objects:
            print(f"no object file in {folder} starts with {', '.join(prefixes)}",
                  file=sys.stderr)
            return 1
        found += check(nm, objects)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
