"""The bundled-FMU table of the guide lists exactly the FMUs the package ships: each of its names
is installed, and each installed FMU is in the table or is a name of the table with `_fmi3` (the
FMI 1.0 builds and the FMI 3.0-only clocked controller have no twin)."""

from __future__ import annotations

import re
from pathlib import Path

from syssimx import fmus

PAGE = Path(__file__).resolve().parents[2] / "docs" / "guide" / "bundled-fmus.md"


def table_names() -> set[str]:
    """The FMU names of the page's table: the backquoted names of each row's first cell."""
    names: set[str] = set()
    for line in PAGE.read_text().splitlines():
        cells = line.split("|")
        if line.startswith("| `") and len(cells) > 2:
            names.update(re.findall(r"`([a-z0-9_]+)`", cells[1]))
    return names


def test_the_table_lists_exactly_the_shipped_fmus() -> None:
    listed = table_names()
    fmi3 = {name + "_fmi3" for name in listed if not re.search(r"_fmi(1|1_me|3)$", name)}
    shipped = set(fmus.available())
    assert shipped, "no bundled FMUs found: is the build installed?"
    assert sorted(listed - shipped) == [], "listed but not shipped"
    assert sorted(shipped - listed - fmi3) == [], "shipped but not listed"
    assert sorted(fmi3 - shipped) == [], "the page says every FMU has an _fmi3 build"
