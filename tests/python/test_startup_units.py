"""Reading an FMU whose units are plain SI symbols needs no pint: units.plainly_readable knows
them, and pint reads each of them with the meaning FMI gives it."""

from __future__ import annotations

import pytest
from syssimx import units

MEANINGS = {
    "m": "meter", "s": "second", "kg": "kilogram", "g": "gram", "K": "kelvin", "A": "ampere",
    "mol": "mole", "cd": "candela", "rad": "radian", "sr": "steradian", "Hz": "hertz",
    "N": "newton", "Pa": "pascal", "J": "joule", "W": "watt", "C": "coulomb", "V": "volt",
    "F": "farad", "ohm": "ohm", "S": "siemens", "Wb": "weber", "T": "tesla", "H": "henry",
    "lm": "lumen", "lx": "lux", "Bq": "becquerel", "Gy": "gray", "Sv": "sievert",
    "kat": "katal", "L": "liter", "l": "liter", "min": "minute", "h": "hour", "d": "day",
    "bar": "bar", "deg": "degree", "mm": "millimeter", "cm": "centimeter", "km": "kilometer",
    "ms": "millisecond", "mg": "milligram", "kN": "kilonewton", "kW": "kilowatt",
    "MW": "megawatt", "kJ": "kilojoule", "MJ": "megajoule", "kPa": "kilopascal",
    "MPa": "megapascal", "mV": "millivolt", "kV": "kilovolt", "mA": "milliampere",
}


def test_every_plain_symbol_means_what_fmi_means_by_it():
    assert set(MEANINGS) == units.PLAIN_SYMBOLS
    for symbol, name in MEANINGS.items():
        assert units.to_unit(symbol) == units.to_unit(name), symbol


@pytest.mark.parametrize(("unit", "pint_unit"), [
    ("kg.m2/s2", "kilogram * meter ** 2 / second ** 2"), ("N.m.s/rad", "meter * newton * "
                                                          "second / radian"),
    ("1/s", "1 / second"), ("s-1", "1 / second"), ("kJ/kg", "kilojoule / kilogram"),
    ("m/s/s", "meter / second ** 2"),
])
def test_plain_units_are_read_by_pint_as_written(unit: str, pint_unit: str):
    assert units.plainly_readable(unit)
    assert str(units.to_unit(unit)) == pint_unit


@pytest.mark.parametrize("unit", ["Ohm", "Nm", "degC", "m/", "m..s", "m-", "bogus", "1/1/s",
                                  " m", "m^2"])
def test_anything_else_is_left_to_pint(unit: str):
    assert not units.plainly_readable(unit)
