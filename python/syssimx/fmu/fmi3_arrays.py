"""FMI 3.0 array variables as scalar ports, one per element.

An array input, output or parameter `y` of shape (2, 3) becomes the scalars `y[0,0]`,
`y[0,1]`, ... `y[1,2]`: FMPy's names for array elements (0-based, row-major, the order in
which FMI 3.0 serializes an array). Each element gets an engine value reference of its own,
above every value reference of the FMU; the engine's FMI 3.0 back-end maps it to the array's
value reference and position and reads and writes the array whole. The sizes are the ones the
description gives: a dimension's `start`, or the start value of the structural parameter it
names, which therefore cannot be changed.
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path
from typing import Any, NamedTuple

from ..errors import FMUFileError

_ARRAY_CAUSALITIES = ("input", "output", "parameter")
_MAX_VALUE_REFERENCE = 2**32 - 1


class ArrayElement(NamedTuple):
    """Where an element's engine value reference points: the array's FMU value reference, the
    element's row-major position, the array's number of elements, the element's start value
    (a number; a Boolean as 1.0 or 0.0)."""

    array_vr: int
    position: int
    size: int
    start: float


class ExpandedVariables(NamedTuple):
    """The variables with each array port replaced by its elements, the element table by
    engine value reference, the outputs' ModelStructure entries likewise, and each structural
    parameter's name with the arrays it sizes."""

    variables: list[Any]
    elements: dict[int, ArrayElement]
    outputs: list[Any]
    structural: dict[str, list[str]]


class ElementVariable:
    """One element of an array variable, read like a scalar variable: its own name, engine
    value reference and start, everything else the array's. Small and made without copying
    the array's variable (attrs.evolve of FMPy's variable cost about 0.3 ms per element)."""

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


def expand_arrays(description: Any, path: Path) -> ExpandedVariables:
    """The FMI 3.0 `description`'s variables with array ports expanded (FMUFileError naming the
    file and variable when an array cannot be)."""
    table = description.modelVariables
    next_vr = max((v.valueReference for v in table), default=-1) + 1
    variables: list[Any] = []
    elements: dict[int, ArrayElement] = {}
    by_array: dict[str, list[Any]] = {}
    structural: dict[str, list[str]] = {}
    for variable in table:
        for dimension in variable.dimensions or ():
            if dimension.variable is not None:
                structural.setdefault(dimension.variable.name, []).append(variable.name)
        if not variable.dimensions or variable.causality not in _ARRAY_CAUSALITIES:
            variables.append(variable)
            continue
        shape = tuple(variable.shape)
        size = math.prod(shape)
        if next_vr + size - 1 > _MAX_VALUE_REFERENCE:
            raise FMUFileError(f"{path}: array {variable.name!r} of {size} elements does not "
                               "fit the value references left above the FMU's")
        starts = _element_starts(variable, size, path)
        parts = []
        for position, index in enumerate(itertools.product(*(range(d) for d in shape))):
            name = f"{variable.name}[{','.join(map(str, index))}]"
            text = None if starts is None else starts[position]
            parts.append(ElementVariable(variable, name, next_vr, text))
            elements[next_vr] = ArrayElement(variable.valueReference, position, size,
                                             _number(text, variable.type))
            next_vr += 1
        by_array[variable.name] = parts
        variables.extend(parts)
    return ExpandedVariables(variables, elements,
                             _expanded_outputs(description.outputs, by_array), structural)


def _element_starts(variable: Any, size: int, path: Path) -> list[str] | None:
    """The array's start values, one text per element (FMI 3.0 lists them space-separated)."""
    if variable.start is None:
        return None
    starts = str(variable.start).split()
    if len(starts) != size:
        raise FMUFileError(f"{path}: array {variable.name!r} has {size} elements but "
                           f"{len(starts)} start values")
    return starts


def _number(text: str | None, fmi_type: str) -> float:
    if text is None:
        return 0.0
    if fmi_type == "Boolean":
        return 1.0 if text in ("true", "1") else 0.0
    return float(text)


def _expanded_outputs(outputs: list[Any], by_array: dict[str, list[Any]]) -> list[Any]:
    """ModelStructure's outputs with an array output replaced by its elements, each depending
    on every element of the arrays its array depends on."""
    import attrs

    expanded = []
    for unknown in outputs:
        dependencies = unknown.dependencies
        if dependencies is not None:
            dependencies = [e for d in dependencies for e in by_array.get(d.name, [d])]
        for variable in by_array.get(unknown.variable.name, [unknown.variable]):
            expanded.append(attrs.evolve(unknown, variable=variable, dependencies=dependencies))
    return expanded
