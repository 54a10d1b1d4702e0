"""The members of an ensemble: one parameter set each, from value lists (grid or zip) or from
the command line's value specifications, kept as a table of columns (ParameterTable)."""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, overload

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
    return list(parameter_table(parameters, mode))


def parameter_table(parameters: Mapping[str, Iterable[Any]], mode: str = "grid"
                    ) -> ParameterTable:
    """parameter_sets' members as a table: a column per parameter, no dict per member."""
    if mode not in MODES:
        raise ConfigurationError(f"ensemble mode must be one of {list(MODES)}, got {mode!r}")
    if not parameters:
        raise ConfigurationError("an ensemble needs at least one parameter to vary")
    names = tuple(_checked_name(name) for name in parameters)
    columns = [_column(name, values) for name, values in parameters.items()]
    if mode == "zip":
        lengths = {name: len(column) for name, column in zip(names, columns, strict=True)}
        if len(set(lengths.values())) > 1:
            raise ConfigurationError(f"zip mode needs value lists of one length, got {lengths}")
        return ParameterTable(names, tuple(columns))
    # every combination, the first column varying slowest: column j repeats each of its values
    # for every combination of the columns after it, and the whole for those before it
    sizes = [len(column) for column in columns]
    return ParameterTable(names, tuple(
        np.tile(np.repeat(column, math.prod(sizes[j + 1:])), math.prod(sizes[:j]))
        for j, column in enumerate(columns)))


@dataclass(frozen=True, eq=False)
class ParameterTable(Sequence[ParameterSet]):
    """Member k's parameter set is {names[j]: columns[j][k]}. A column of numbers of one type
    is an int64, float64 or bool array (its values given back as Python's int, float, bool);
    any other (strings, mixed types) an array of the Python values themselves. What a chunk of
    members sends to its worker is a slice of it: a few arrays, not a dict per member
    (2000 dicts cost the client 3.4 ms to make, and a pickle each)."""

    names: tuple[str, ...]
    columns: tuple[np.ndarray, ...]

    @classmethod
    def of(cls, sets: Sequence[ParameterSet]) -> ParameterTable:
        """The table of parameter sets that name the same parameters (the first set's)."""
        names = tuple(sets[0]) if sets else ()
        return cls(names, tuple(_typed([values[name] for values in sets]) for name in names))

    def __len__(self) -> int:
        return len(self.columns[0]) if self.columns else 0

    def __eq__(self, other: object) -> bool:
        """The same parameter sets, member by member."""
        return isinstance(other, ParameterTable) and self.names == other.names and all(
            np.array_equal(mine, theirs) for mine, theirs in zip(self.columns, other.columns,
                                                                  strict=True))

    @overload
    def __getitem__(self, index: int) -> ParameterSet: ...

    @overload
    def __getitem__(self, index: slice) -> ParameterTable: ...

    def __getitem__(self, index: int | slice) -> ParameterSet | ParameterTable:
        if isinstance(index, slice):
            return ParameterTable(self.names, tuple(column[index] for column in self.columns))
        if not -len(self) <= index < len(self):
            raise IndexError(f"member {index} of {len(self)}")
        return {name: _plain(column[index])
                for name, column in zip(self.names, self.columns, strict=True)}

    def __iter__(self) -> Iterator[ParameterSet]:
        return (self[k] for k in range(len(self)))

    def column(self, name: str) -> np.ndarray:
        """The values of `name` for every member: numbers as a numeric array, else objects."""
        values = self.columns[self.names.index(name)]
        if values.dtype != object:
            return values
        array = np.array(values.tolist())
        return array if array.dtype.kind in "biuf" else values


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


def _column(name: str, values: Iterable[Any]) -> np.ndarray:
    """The values of one varied parameter as a column (see ParameterTable)."""
    if isinstance(values, str | bytes) or not isinstance(values, Iterable):
        raise ConfigurationError(f"{name}: expected a list of values, got {values!r}")
    if isinstance(values, np.ndarray) and values.size and values.dtype.kind in "biuf":
        # numbers already: their Python values are these, at 64 bits (a float32 is exactly a
        # float64); an unsigned integer past int64 keeps its exact Python value
        array = values.ravel()
        if array.dtype.kind == "u" and array.max() > np.iinfo(np.int64).max:
            return _typed(array.tolist())
        kind = {"b": np.bool_, "i": np.int64, "u": np.int64, "f": np.float64}[array.dtype.kind]
        return array.astype(kind)
    # tolist: numpy's values as Python's, at once
    listed = values.ravel().tolist() if isinstance(values, np.ndarray) else list(values)
    if not listed:
        raise ConfigurationError(f"{name}: the list of values is empty")
    return _typed([_scalar(name, value) for value in listed])


def _typed(values: list[Any]) -> np.ndarray:
    """Plain values as a column: an int64, float64 or bool array where all are of that one
    Python type (and an int fits), else an array of the values themselves."""
    kinds = {type(value) for value in values}
    if len(kinds) == 1 and (kind := kinds.pop()) in (bool, int, float):
        try:
            return np.array(values, dtype={bool: np.bool_, int: np.int64, float: np.float64}[kind])
        except OverflowError:  # an int past int64
            pass
    column = np.empty(len(values), dtype=object)
    column[:] = values
    return column


def _plain(value: Any) -> Scalar:
    """A column's value as the Python value it was given as."""
    return value.item() if isinstance(value, np.generic) else value


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

