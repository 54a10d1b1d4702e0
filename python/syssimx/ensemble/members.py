"""The members of an ensemble: one parameter set each, from value lists (grid or zip) or from
the command line's value specifications."""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import numpy as np

from ..core.literal import literal
from ..errors import ConfigurationError

MODES = ("grid", "zip")

Scalar = bool | int | float | str
ParameterSet = dict[str, Scalar]
PLAIN = (bool, int, float, str)  # a value of one of these types exactly is kept as it is


def parameter_sets(parameters: Mapping[str, Iterable[Any]], mode: str = "grid"
                   ) -> list[ParameterSet]:
    """One {"Component.parameter": value} per member: every combination of the value lists
    ("grid", the first parameter varying slowest) or their i-th values together ("zip", lists
    of one length)."""
    if mode not in MODES:
        raise ConfigurationError(f"ensemble mode must be one of {list(MODES)}, got {mode!r}")
    if not parameters:
        raise ConfigurationError("an ensemble needs at least one parameter to vary")
    names = [_checked_name(name) for name in parameters]
    columns = [[_scalar(name, v) for v in _values(name, values)]
               for name, values in parameters.items()]
    if mode == "zip":
        lengths = {name: len(column) for name, column in zip(names, columns, strict=True)}
        if len(set(lengths.values())) > 1:
            raise ConfigurationError(f"zip mode needs value lists of one length, got {lengths}")
        combinations: Iterable[tuple[Scalar, ...]] = zip(*columns, strict=True)
    else:
        combinations = itertools.product(*columns)
    return [dict(zip(names, values, strict=True)) for values in combinations]


def split_name(name: str) -> tuple[str, str]:
    """"Component.parameter" -> (component, parameter); the component is before the first
    dot, so a parameter name may contain dots itself (FMI structured names)."""
    component, _, parameter = _checked_name(name).partition(".")
    return component, parameter


def parse_values(text: str) -> list[Scalar]:
    """The values of a command-line specification: "START:STOP:COUNT" (COUNT evenly spaced
    values, both ends included), "A,B,C" or a single value."""
    if text.count(":") == 2:
        start, stop, count = (part.strip() for part in text.split(":"))
        try:
            first, last, number = float(start), float(stop), int(count)
        except ValueError:
            raise ConfigurationError(f"expected START:STOP:COUNT with numbers and an integer "
                                     f"count, got {text!r}") from None
        if number < 1:
            raise ConfigurationError(f"{text!r}: the count must be at least 1")
        return [float(v) for v in np.linspace(first, last, number)]
    values = [literal(part.strip()) for part in text.split(",")]
    if any(part == "" for part in values):
        raise ConfigurationError(f"empty value in {text!r}")
    return values


def _checked_name(name: Any) -> str:
    if not isinstance(name, str) or "." not in name.strip(".") or name.startswith("."):
        raise ConfigurationError(f"a varied parameter is named 'Component.parameter', "
                                 f"got {name!r}")
    return name


def _values(name: str, values: Iterable[Any]) -> Sequence[Any]:
    if isinstance(values, str | bytes) or not isinstance(values, Iterable):
        raise ConfigurationError(f"{name}: expected a list of values, got {values!r}")
    # tolist: numpy's values as Python's, at once
    listed = values.ravel().tolist() if isinstance(values, np.ndarray) else list(values)
    if not listed:
        raise ConfigurationError(f"{name}: the list of values is empty")
    return listed


def _scalar(name: str, value: Any) -> Scalar:
    """A plain Python value (numpy scalars unwrapped), so members pickle and print simply."""
    if type(value) in PLAIN:
        return value
    if isinstance(value, np.generic):
        value = value.item()
    if not isinstance(value, bool | int | float | str):
        raise ConfigurationError(f"{name}: values must be numbers, booleans or strings, got "
                                 f"{type(value).__name__} {value!r}")
    return value

