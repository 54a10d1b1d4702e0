"""FMI 3.0 array variables as ports, one per element, made when asked for.

An array input, output or parameter `y` of shape (2, 3) stands for the scalar ports `y[0,0]`,
`y[0,1]`, ... `y[1,2]`: FMPy's names for array elements (0-based, row-major, the order in
which FMI 3.0 serializes an array). Each element has an engine value reference of its own,
above every value reference of the FMU (the array's first element's plus its position); the
engine's FMI 3.0 back-end maps it to the array's value reference and position and reads and
writes the array whole. The sizes are the ones the description gives: a dimension's `start`,
or the start value of the structural parameter it names, which therefore cannot be changed.

An array is kept as one ArrayPort (its variable, first engine value reference, shape and
start values as a numpy array); the maps of ports, parameters and starts make an element's
objects when it is looked up (core/element_map.py), so that an array of 10**5 elements costs
what its start values do.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from ..core.element_map import Block
from ..errors import FMUFileError

_ARRAY_CAUSALITIES = ("input", "output", "parameter")
_MAX_VALUE_REFERENCE = 2**32 - 1
_INTEGER_TYPES = ("Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32", "Int64", "UInt64",
                  "Enumeration")


class ArrayPort(NamedTuple):
    """An array input, output or parameter: FMPy's variable, the engine value reference of
    its first element, its shape, and its start values in row-major order (None when it
    declares none): float64 for Float types, int64 or uint64 for integers, bool for
    Boolean."""

    variable: Any
    first_vr: int
    shape: tuple[int, ...]
    starts: np.ndarray | None

    @property
    def name(self) -> str:
        return str(self.variable.name)

    @property
    def causality(self) -> str:
        return str(self.variable.causality)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    def start(self, position: int) -> float | int | bool | None:
        """The element's start value as a Python number (None when the array has none)."""
        return None if self.starts is None else self.starts[position].item()

    def element(self, position: int, name: str) -> ElementVariable:
        start = self.start(position)
        text = None if start is None else \
            ("true" if start else "false") if isinstance(start, bool) else repr(start)
        return ElementVariable(self.variable, name, self.first_vr + position, text)


class ArrayVariables(NamedTuple):
    """The FMI 3.0 description's variables in document order, each array port as its
    ArrayPort and every other variable as itself, and each structural parameter's name with
    the arrays it sizes."""

    in_order: list[Any]
    structural: dict[str, list[str]]


class ElementVariable:
    """One element of an array variable, read like a scalar variable: its own name, engine
    value reference and start, everything else the array's."""

    __slots__ = ("array", "name", "start", "valueReference")
    dimensions: tuple[Any, ...] = ()
    shape: tuple[int, ...] = ()

    def __init__(self, array: Any, name: str, value_reference: int, start: str | None) -> None:
        self.array = array
        self.name = name
        self.valueReference = value_reference
        self.start = start

    def __getattr__(self, attribute: str) -> Any:  # only for what the element does not hold
        return getattr(self.array, attribute)


class ElementsInPlace:
    """The variables `in_order` (array_variables') with each ArrayPort's elements in its
    place, made while iterated."""

    def __init__(self, in_order: list[Any]) -> None:
        self._in_order = in_order

    def __iter__(self) -> Iterator[Any]:
        for variable in self._in_order:
            if isinstance(variable, ArrayPort):
                block = Block(variable.name, variable.shape, variable.element)
                for position, name in enumerate(block.names()):
                    yield variable.element(position, name)
            else:
                yield variable


def array_variables(description: Any, path: Path) -> ArrayVariables:
    """The FMI 3.0 `description`'s variables with its array ports as ArrayPorts (FMUFileError
    naming the file and variable when an array cannot be one)."""
    table = description.modelVariables
    next_vr = max((v.valueReference for v in table), default=-1) + 1
    in_order: list[Any] = []
    structural: dict[str, list[str]] = {}
    for variable in table:
        for dimension in variable.dimensions or ():
            if dimension.variable is not None:
                structural.setdefault(dimension.variable.name, []).append(variable.name)
        if not variable.dimensions or variable.causality not in _ARRAY_CAUSALITIES:
            in_order.append(variable)
            continue
        shape = tuple(int(extent) for extent in variable.shape)
        size = math.prod(shape)
        if next_vr + size - 1 > _MAX_VALUE_REFERENCE:
            raise FMUFileError(f"{path}: array {variable.name!r} of {size} elements does not "
                               "fit the value references left above the FMU's")
        in_order.append(ArrayPort(variable, next_vr, shape, _starts(variable, size, path)))
        next_vr += size
    return ArrayVariables(in_order, structural)


def _starts(variable: Any, size: int, path: Path) -> np.ndarray | None:
    """The array's start values (FMI 3.0 lists them space-separated; description_fmi3.py has
    checked that each parses as the type)."""
    if variable.start is None:
        return None
    texts = str(variable.start).split()
    if len(texts) != size:
        raise FMUFileError(f"{path}: array {variable.name!r} has {size} elements but "
                           f"{len(texts)} start values")
    if variable.type == "Boolean":
        return np.isin(np.array(texts), ("true", "1"))
    if variable.type in _INTEGER_TYPES:
        return np.array(texts, dtype=np.uint64 if variable.type == "UInt64" else np.int64)
    return np.array(texts, dtype=np.float64)
