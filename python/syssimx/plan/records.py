"""The text of a plan (format `syssimx-plan 1`): one record a line, a keyword and its fields.

Fields are written by their Python type: a flag as `bool`, an integer as `int`, a double as
`float` (as the engine's writer writes it), a fixed word as `Word`, a string as `str` or `bytes`
(quoted, escaped), a list as a `list` of items (its count first; an item of several fields a
tuple), a long list of doubles (a table's column) as `Doubles`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import TypeAlias

import numpy as np

from ..core.port import PortType

HEADER = "syssimx-plan 1"


class Word(str):
    """A fixed word of the format (`real`, `jacobi`, ...), written bare."""


# a list of more doubles than this is written in its hex form, as the engine's writer does
# (PLAN_DECIMAL_DOUBLES_MAX): a short list stays readable
DECIMAL_DOUBLES_MAX = 64


class Doubles:
    """A list of doubles (a table's times or column). Up to DECIMAL_DOUBLES_MAX values: its
    count, then each value as a double field is written (`0.1`, `100`, `1e-10`, `nan`,
    `-inf`). A longer list in its hex form, exact and with no formatting per value: `x`, the
    count, `:`, then the values' IEEE-754 binary64 bytes, little-endian, as lowercase hex in
    one token."""

    def __init__(self, values: np.ndarray) -> None:
        self.values = np.asarray(values, dtype=np.float64)

    def text(self) -> str:
        if len(self.values) > DECIMAL_DOUBLES_MAX:
            return f"x{len(self.values)}:" + self.values.astype("<f8").tobytes().hex()
        values = self.values.tolist()
        return " ".join((str(len(values)), *map(_double, values)))


Field: TypeAlias = \
    "bool | int | float | str | bytes | Doubles | list[Field] | tuple[Field, ...]"

# the characters a string writes escaped; every other control character (and, in bytes, every
# byte outside ASCII) as \xHH
_ESCAPES = {'"': '\\"', "\\": "\\\\", "\n": "\\n", "\t": "\\t"}


def _double(value: float) -> str:
    if math.isnan(value):
        return "nan"
    if math.isinf(value):
        return "inf" if value > 0 else "-inf"
    # the fewest of 15, 16 or 17 significant digits that read back to the value, as the
    # engine's writer writes it
    return next(text for digits in (15, 16, 17) for text in (f"{value:.{digits}g}",)
                if digits == 17 or float(text) == value)


def _character(char: str, ascii_only: bool) -> str:
    escape = _ESCAPES.get(char)
    if escape is not None:
        return escape
    code = ord(char)
    return f"\\x{code:02x}" if code < 0x20 or code == 0x7F or (ascii_only and code > 0x7F) \
        else char


def _string(value: str | bytes) -> str:
    """A quoted string: a text as its characters, bytes (a Binary value) byte by byte."""
    chars = value.decode("latin-1") if isinstance(value, bytes) else value
    return '"' + "".join(_character(c, isinstance(value, bytes)) for c in chars) + '"'


def _fields(values: Iterable[Field]) -> Iterable[str]:
    for value in values:
        if isinstance(value, bool):
            yield "1" if value else "0"
        elif isinstance(value, int):
            yield str(value)
        elif isinstance(value, float):
            yield _double(value)
        elif isinstance(value, Word):
            yield str(value)
        elif isinstance(value, str | bytes):
            yield _string(value)
        elif isinstance(value, list):
            yield str(len(value))
            yield from _fields(value)
        elif isinstance(value, Doubles):
            yield value.text()
        else:  # an item of several fields
            yield from _fields(value)


class PlanRecords:
    """The records of one plan in the order they are added, each with what it is about (its
    component or connection, named as the user named them) for messages."""

    def __init__(self) -> None:
        self.records: list[tuple[str, tuple[Field, ...], str]] = []

    def add(self, keyword: str, *fields: Field, about: str = "") -> None:
        self.records.append((keyword, fields, about))

    def about(self, line: int) -> str:
        """What the record on line `line` of the text (the header is line 1) is about."""
        return self.records[line - 2][2] if 2 <= line <= len(self.records) + 1 else ""

    def text(self) -> str:
        lines = [HEADER, *(" ".join((keyword, *_fields(fields)))
                           for keyword, fields, _ in self.records)]
        return "\n".join(lines) + "\n"

    def extended(self, *more: PlanRecords) -> PlanRecords:
        """These records followed by those of `more`."""
        joined = PlanRecords()
        joined.records = [*self.records, *(r for extra in more for r in extra.records)]
        return joined


_VALUE_TYPES = {PortType.REAL: "real", PortType.INT: "integer", PortType.BOOL: "boolean",
                PortType.STRING: "string", PortType.BINARY: "binary"}


def value_type_word(kind: PortType) -> Word:
    """The word of a port's value type (the engine's ssx_value_type)."""
    return Word(_VALUE_TYPES[kind])
