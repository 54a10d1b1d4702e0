"""Physical units: one pint registry for the package and the translation of FMI unit strings.

pint and its registry cost more than the rest of `import syssimx` together, so they are loaded on
the first unit operation: `ureg`, `Quantity` and `DimensionalityError` are module attributes
resolved on first access, and `is_quantity` answers without importing pint at all.
"""

from __future__ import annotations

import hashlib
import re
import sys
from functools import cache, lru_cache
from typing import TYPE_CHECKING, Any

from .errors import ConfigurationError

if TYPE_CHECKING:
    import pint


@cache
def registry() -> pint.UnitRegistry:
    """The package's one pint registry, built on first use."""
    import pint

    return pint.UnitRegistry()


def __getattr__(name: str) -> Any:
    """`ureg`, `Quantity` and `DimensionalityError` on first access (see the module docstring)."""
    if name == "ureg":
        return registry()
    if name == "Quantity":
        return registry().Quantity
    if name == "DimensionalityError":
        import pint

        return pint.DimensionalityError
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def is_quantity(value: object) -> bool:
    """Whether `value` is a pint quantity; nothing can be one before pint is imported."""
    pint = sys.modules.get("pint")
    return pint is not None and isinstance(value, pint.Quantity)


def quantity(magnitude: float, unit: str) -> pint.Quantity:
    """`magnitude` in the FMI or pint unit `unit`."""
    return registry().Quantity(magnitude, to_unit(unit))


# FMI writes products with '.' and powers as trailing integers ("kg.m2", "m/s2", "s-1").
_PRODUCT = re.compile(r"(?<=[A-Za-z0-9])\.(?=[A-Za-z])")
_POWER = re.compile(r"(?<=[A-Za-z])(-?\d+)")


def pint_expression(unit: str) -> str:
    """The pint spelling of an FMI unit string, e.g. "kg.m2" -> "kg*m**2"."""
    expression = _PRODUCT.sub("*", unit.strip())
    return _POWER.sub(r"**\1", expression)


# What tools write for "no physical unit" (Parker and Hopsan export "-").
DIMENSIONLESS_SPELLINGS = frozenset({"", "1", "-"})

# Unit symbols pint reads as written, with the meaning FMI gives them (the tests hold pint to
# each one's name). A unit made of these alone, joined by '.' and '/' with integer powers, is
# known to be readable without importing pint, so reading a typical FMU does not import it.
PLAIN_SYMBOLS = frozenset({
    "m", "s", "kg", "g", "K", "A", "mol", "cd", "rad", "sr", "Hz", "N", "Pa", "J", "W", "C",
    "V", "F", "ohm", "S", "Wb", "T", "H", "lm", "lx", "Bq", "Gy", "Sv", "kat", "L", "l", "min",
    "h", "d", "bar", "deg", "mm", "cm", "km", "ms", "mg", "kN", "kW", "MW", "kJ", "MJ", "kPa",
    "MPa", "mV", "kV", "mA",
})
_FACTOR = re.compile(r"([A-Za-z]+)(?:-?\d+)?")


def plainly_readable(unit: str) -> bool:
    """Whether `unit` is made of PLAIN_SYMBOLS only (then pint reads it as written); False
    says nothing: pint may still read it."""
    factors = unit.removeprefix("1/").replace("/", ".").split(".")
    return all((match := _FACTOR.fullmatch(factor)) is not None
               and match.group(1) in PLAIN_SYMBOLS for factor in factors)


@lru_cache(maxsize=512)
def to_unit(unit: str) -> pint.Unit:
    """Parse an FMI or pint unit string; "1", "-" and "" are dimensionless.

    Raises ValueError naming the unit for anything pint cannot read (pint itself raises many
    kinds, some without a message, e.g. an AssertionError for "m/s/").
    """
    if unit.strip() in DIMENSIONLESS_SPELLINGS:
        return registry().dimensionless
    try:
        return registry().Unit(pint_expression(unit))
    except Exception as exc:  # whatever pint raises, the unit is unreadable
        reason = str(exc) or type(exc).__name__
        raise ConfigurationError(f"unit {unit!r} is unknown to pint ({reason})") from exc


@lru_cache(maxsize=512)
def conversion(src_unit: str | None, dst_unit: str | None) -> tuple[float, float]:
    """(scale, offset) with dst = scale * src + offset. A side without unit takes the other's.

    Raises pint.DimensionalityError when the units measure different quantities. Cached: a
    large system connects many ports of a few units.
    """
    if not src_unit or not dst_unit or src_unit == dst_unit:  # no pint needed
        return 1.0, 0.0
    src, dst = to_unit(src_unit), to_unit(dst_unit)
    zero = registry().Quantity(0.0, src).to(dst).magnitude
    one = registry().Quantity(1.0, src).to(dst).magnitude
    return float(one - zero), float(zero)


# The SI base units a unit definition (SSP's ssc:BaseUnit, FMI's BaseUnit) raises to powers.
BASE_UNITS = ("kg", "m", "s", "A", "K", "mol", "cd", "rad")


def si_expression(exponents: tuple[int, ...]) -> str:
    """The SI base units with `exponents` (in BASE_UNITS order) as pint reads them."""
    factors = [unit if power == 1 else f"{unit}**{power}"
               for unit, power in zip(BASE_UNITS, exponents, strict=True) if power]
    return "*".join(factors) or "dimensionless"


_HEX_AS_LETTERS = str.maketrans("0123456789", "ghijklmnop")


def defined_unit(label: str, exponents: tuple[int, ...], factor: float, offset: float) -> str:
    """A unit pint reads for a unit defined by its base units (value in SI = factor * value +
    offset), whatever its label says. A pure product of base units is written as one; any
    other is entered in the registry under a name made of its label and its definition, so
    two files that give one label different meanings do not meet."""
    si = si_expression(exponents)
    if factor == 1.0 and offset == 0.0:
        return si
    # letters only: FMI's spelling reads a digit after a letter as a power
    digest = hashlib.sha1(repr((exponents, factor, offset)).encode()).hexdigest()[:8]
    stem = re.sub(r"[^A-Za-z]+", "_", label).strip("_") or "unit"
    name = f"{stem}_{digest.translate(_HEX_AS_LETTERS)}"
    units = registry()
    if name not in units:
        units.define(f"{name} = {factor!r} * ({si}); offset: {offset!r}")
    return name


def magnitude_in(value: object, unit: str | None) -> float:
    """A number or a pint quantity as a float in `unit` (a plain number is taken as in `unit`)."""
    if is_quantity(value):
        if unit is None:
            return float(value.to(registry().dimensionless).magnitude)  # type: ignore[attr-defined]
        return float(value.to(to_unit(unit)).magnitude)  # type: ignore[attr-defined]
    return float(value)  # type: ignore[arg-type]
