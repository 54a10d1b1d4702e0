"""The units an FMU defines in its modelDescription (UnitDefinitions/Unit/BaseUnit, FMI 2.0 and
3.0): a unit whose name pint does not know is read by its definition, SI base unit exponents
with a factor and an offset, as pint reads it. Read only when a port's unit is unknown to pint
(the FMU's own file, parsed once more: rare, and the usual FMU never pays for it)."""

from __future__ import annotations

import zipfile
from pathlib import Path

from ..units import BASE_UNITS, defined_unit


def unit_definitions(path: Path) -> dict[str, str]:
    """Each unit the FMU at `path` defines by a BaseUnit, by name, as pint reads it; a
    definition that is no number is left out (the unit then stays unknown)."""
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)
    with zipfile.ZipFile(path) as archive:
        root = etree.fromstring(archive.read("modelDescription.xml"), parser)
    units = {}
    for unit in root.iterfind("UnitDefinitions/Unit"):
        base = unit.find("BaseUnit")
        name = unit.get("name")
        if base is None or not name:
            continue
        try:
            exponents = tuple(int(base.get(symbol, "0")) for symbol in BASE_UNITS)
            factor, offset = float(base.get("factor", "1")), float(base.get("offset", "0"))
        except ValueError:
            continue
        units[name] = defined_unit(name, exponents, factor, offset)
    return units
