"""Physical units: one pint registry for the package and the translation of FMI unit strings."""

from __future__ import annotations

import re
from functools import lru_cache

import pint

ureg = pint.UnitRegistry()
Quantity = ureg.Quantity

# FMI writes products with '.' and powers as trailing integers ("kg.m2", "m/s2", "s-1").
_PRODUCT = re.compile(r"(?<=[A-Za-z0-9])\.(?=[A-Za-z])")
_POWER = re.compile(r"(?<=[A-Za-z])(-?\d+)")


def pint_expression(unit: str) -> str:
    """The pint spelling of an FMI unit string, e.g. "kg.m2" -> "kg*m**2"."""
    expression = _PRODUCT.sub("*", unit.strip())
    return _POWER.sub(r"**\1", expression)


# What tools write for "no physical unit" (Parker and Hopsan export "-").
DIMENSIONLESS_SPELLINGS = frozenset({"", "1", "-"})


@lru_cache(maxsize=512)
def to_unit(unit: str) -> pint.Unit:
    """Parse an FMI or pint unit string; "1", "-" and "" are dimensionless.

    Raises ValueError naming the unit for anything pint cannot read (pint itself raises many
    kinds, some without a message, e.g. an AssertionError for "m/s/").
    """
    if unit.strip() in DIMENSIONLESS_SPELLINGS:
        return ureg.dimensionless
    try:
        return ureg.Unit(pint_expression(unit))
    except Exception as exc:  # whatever pint raises, the unit is unreadable
        reason = str(exc) or type(exc).__name__
        raise ValueError(f"unit {unit!r} is unknown to pint ({reason})") from exc


def conversion(src_unit: str | None, dst_unit: str | None) -> tuple[float, float]:
    """(scale, offset) with dst = scale * src + offset. A side without unit takes the other's.

    Raises pint.DimensionalityError when the units measure different quantities.
    """
    if not src_unit or not dst_unit:
        return 1.0, 0.0
    src, dst = to_unit(src_unit), to_unit(dst_unit)
    zero = Quantity(0.0, src).to(dst).magnitude
    one = Quantity(1.0, src).to(dst).magnitude
    return float(one - zero), float(zero)


def magnitude_in(value: object, unit: str | None) -> float:
    """A number or a pint quantity as a float in `unit` (a plain number is taken as in `unit`)."""
    if isinstance(value, pint.Quantity):
        if unit is None:
            return float(value.to(ureg.dimensionless).magnitude)
        return float(value.to(to_unit(unit)).magnitude)
    return float(value)  # type: ignore[arg-type]
