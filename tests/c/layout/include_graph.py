"""Checks that the engine's files include one another without a circle.

A room is a source file with the header of the same name (coupling.c with coupling.h); a header
without a source is a room of its own. Room A needs room B when a file of A includes a header of
B. No room may need a room that needs it back: a circle is printed with the includes that close
it, and the check fails.

Usage: include_graph.py SRC_DIR
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)


def rooms_of(src: Path) -> tuple[dict[str, str], dict[str, set[str]]]:
    """Each file's room, and each room's includes as (room, header name) pairs resolved."""
    files = sorted(p for p in src.rglob("*") if p.suffix in (".c", ".h"))
    room_of = {p.name: p.stem for p in files}
    headers = {p.name for p in files if p.suffix == ".h"}
    needs: dict[str, set[str]] = {p.stem: set() for p in files}
    for path in files:
        for name in INCLUDE.findall(path.read_text(encoding="utf-8")):
            header = Path(name).name
            if header in headers and room_of[header] != path.stem:
                needs[path.stem].add(room_of[header])
    return room_of, needs


def circles(needs: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected groups of more than one room (Tarjan's algorithm, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    found: list[list[str]] = []
    for root in sorted(needs):
        if root in index:
            continue
        work = [(root, iter(sorted(needs[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            room, successors = work[-1]
            advanced = False
            for nxt in successors:
                if nxt not in index:
                    index[nxt] = low[nxt] = len(index)
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, iter(sorted(needs[nxt]))))
                    advanced = True
                    break
                if nxt in on_stack:
                    low[room] = min(low[room], index[nxt])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[room])
            if low[room] == index[room]:
                group = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    group.append(member)
                    if member == room:
                        break
                if len(group) > 1:
                    found.append(sorted(group))
    return found


def main(argv: list[str]) -> int:
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    src = Path(argv[1])
    _, needs = rooms_of(src)
    found = circles(needs)
    for group in found:
        members = set(group)
        print("circle: " + ", ".join(group))
        for room in group:
            for other in sorted(needs[room] & members):
                print(f"  {room} includes {other}")
    if not needs:
        print(f"no C files under {src}", file=sys.stderr)
        return 1
    print(f"{len(needs)} rooms, {len(found)} circles")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
