"""Checks that the engine's folders are layers: each includes only those below it.

The layers are read from layers.txt beside this script, bottom first; a line may name several
folders, which then form one layer and include nothing of each other. A file belongs to the
longest listed folder that holds it. A quoted include is resolved as the compiler does for the
engine: the including file's own folder first, then every folder of src/ (the engine's include
path names each of them, so a header's name is unique). Every include that goes up or sideways
is printed with the file, the header and the two folders, and the check fails; so does a file
outside every listed folder, a listed folder that is not there, and a header name that is not
unique.

Given `nm` and the object folders of binaries built from src/, the calls are checked the same
way: no object uses a function or table that an object of a higher or sideways folder defines
(a declaration in a lower header with its definition above would pass the includes). meson
names an object after its path with "/" as "_" (stepping/events/hybrid.c is
stepping_events_hybrid.c.o).

Usage: layers.py SRC_DIR [NM OBJECT_DIR...]
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)
LAYERS_FILE = Path(__file__).with_name("layers.txt")


def read_layers(text: str) -> dict[str, int]:
    """Each listed folder's layer, 0 at the bottom."""
    level: dict[str, int] = {}
    lines = [line.split("#", 1)[0].split() for line in text.splitlines()]
    for number, folders in enumerate(line for line in lines if line):
        for folder in folders:
            if folder in level:
                raise ValueError(f"{folder} is listed twice")
            level[folder] = number
    return level


def folder_of(relative: Path, level: dict[str, int]) -> str | None:
    """The longest listed folder holding the file, or None."""
    for parent in relative.parents:
        if parent.as_posix() in level:
            return parent.as_posix()
    return None


def violations(src: Path, level: dict[str, int]) -> list[str]:
    files = sorted(p for p in src.rglob("*") if p.suffix in (".c", ".h"))
    by_name: dict[str, list[Path]] = {}
    for path in files:
        if path.suffix == ".h":
            by_name.setdefault(path.name, []).append(path)
    found = [f"header name {name} is not unique: "
             + ", ".join(p.relative_to(src).as_posix() for p in paths)
             for name, paths in sorted(by_name.items()) if len(paths) > 1]
    for path in files:
        relative = path.relative_to(src)
        room = folder_of(relative, level)
        if room is None:
            found.append(f"{relative.as_posix()}: in no folder of {LAYERS_FILE.name}")
            continue
        for name in INCLUDE.findall(path.read_text(encoding="utf-8")):
            beside = path.parent / name
            if beside.is_file():
                target = beside.resolve()
            elif Path(name).name in by_name:
                target = by_name[Path(name).name][0]
            else:
                continue  # a header from outside the engine (FMI, SUNDIALS)
            other = folder_of(target.relative_to(src), level)
            if other is None or other == room:
                continue
            if level[other] >= level[room]:
                way = "sideways" if level[other] == level[room] else "up"
                found.append(f"{relative.as_posix()} includes {name}: {room} -> {other} ({way})")
    return found


DEFINED = frozenset("TDRBCGSV")


def object_folder(obj: Path, level: dict[str, int]) -> str | None:
    """The listed folder an object was compiled from, by the name meson gives it."""
    for folder in sorted(level, key=len, reverse=True):
        if obj.name.startswith(folder.replace("/", "_") + "_"):
            return folder
    return None


def call_violations(nm: str, objects: Path, level: dict[str, int]) -> list[str]:
    """The calls of one binary's objects that go up or sideways."""
    defined_in: dict[str, Path] = {}
    used: dict[Path, set[str]] = {}
    for obj in sorted(objects.glob("*.o")):
        listing = subprocess.run([nm, "-g", str(obj)], capture_output=True, text=True,
                                 check=True)
        used[obj] = set()
        for fields in (line.split() for line in listing.stdout.splitlines()):
            if len(fields) == 2 and fields[0] == "U":
                used[obj].add(fields[1])
            elif len(fields) == 3 and fields[1] in DEFINED:
                defined_in[fields[2]] = obj
    found = []
    for obj, symbols in used.items():
        room = object_folder(obj, level)
        for symbol in sorted(symbols):
            target = defined_in.get(symbol)
            other = None if target is None else object_folder(target, level)
            if room is None or other is None or other == room or level[other] < level[room]:
                continue
            way = "sideways" if level[other] == level[room] else "up"
            found.append(f"{obj.name} calls {symbol} of {target.name}: {room} -> {other} ({way})")
    return found


def main(argv: list[str]) -> int:
    if len(argv) < 2 or len(argv) == 3:
        print(__doc__, file=sys.stderr)
        return 2
    src = Path(argv[1]).resolve()
    level = read_layers(LAYERS_FILE.read_text(encoding="utf-8"))
    if not level:
        print(f"no folders in {LAYERS_FILE}", file=sys.stderr)
        return 1
    found = [f"{folder}: listed in {LAYERS_FILE.name}, not a folder of {src}"
             for folder in sorted(level) if not (src / folder).is_dir()]
    found += violations(src, level)
    for objects in argv[3:]:
        found += call_violations(argv[2], Path(objects), level)
    for line in found:
        print(line)
    print(f"{len(level)} folders in {max(level.values()) + 1} layers, {len(found)} violations")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
