"""Unit conversion between connectors from the units an SSD defines (ssc:Units): each unit is
a factor and offset to SI base units, so two units with the same base exponents convert
without pint. A defined unit's name is only a label (OMSimulator writes "[m]"): where it meets
an FMU's unit it is read by its definition. Units the SSD does not define are left to pint by
the System."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..ssp_format.documents import NS
from ..units import BASE_UNITS, defined_unit


@dataclass(frozen=True)
class UnitDefinition:
    name: str
    exponents: tuple[int, ...]
    factor: float  # value in SI = factor * value + offset
    offset: float

    def pint_unit(self) -> str:
        """The unit as pint reads it, by its definition."""
        return defined_unit(self.name, self.exponents, self.factor, self.offset)


def read_units(root: Any, prefix: str = "ssd") -> dict[str, UnitDefinition]:
    """The ssc:Unit definitions of an SSD (or, with `prefix` "ssv", of a parameter set), by
    name."""
    units = {}
    for unit in root.iterfind(f"{prefix}:Units/ssc:Unit", NS):
        base = unit.find("ssc:BaseUnit", NS)
        units[unit.get("name")] = UnitDefinition(
            unit.get("name"), tuple(int(base.get(e, 0)) for e in BASE_UNITS),
            float(base.get("factor", 1.0)), float(base.get("offset", 0.0)))
    return units


def defined_conversion(units: dict[str, UnitDefinition], src: str | None,
                       dst: str | None) -> tuple[float, float] | None:
    """(scale, offset) with dst = scale * src + offset when the SSD defines both units, else
    None. Raises ValueError when the definitions measure different quantities."""
    if src not in units or dst not in units:
        return None
    a, b = units[src], units[dst]  # type: ignore[index]
    if a.exponents != b.exponents:
        raise ValueError(f"units {src!r} and {dst!r} measure different quantities")
    return a.factor / b.factor, (a.offset - b.offset) / b.factor
