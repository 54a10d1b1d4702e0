"""The variables of a modelDescription, kept as the engine's reader read them: one array per
field, the texts in one string pool. A ScalarVariable object (fmpy's attribute names) is made
only for the variable asked for, so a model of 10**6 variables costs a few bytes per variable
until its inputs, outputs and parameters are picked out.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Any, overload

import numpy as np

from ..engine import ffi, lib

if TYPE_CHECKING:
    from fmpy.model_description import SimpleType

_BATCH = 4096  # variables made at a time when all are iterated


@dataclass(slots=True, eq=False)
class ScalarVariable:
    """One ScalarVariable, with fmpy's attribute names; `start` is the text of the XML."""

    name: str
    valueReference: int  # noqa: N815 (fmpy's names)
    type: str
    causality: str
    variability: str
    initial: str | None
    description: str | None
    unit: str | None
    declaredType: SimpleType | None  # noqa: N815
    start: str | None


@lru_cache(maxsize=1)
def words() -> tuple[str, ...]:
    """The engine's FMI words by code ("" for none): "parameter", ..., "Real", ..."""
    engine = lib()
    return tuple(ffi.string(engine.ssx_md_word_text(code)).decode()
                 for code in range(engine.SSX_MD_WORD_COUNT))


class VariableTable(Sequence[ScalarVariable]):
    """All variables in document order, as a sequence of ScalarVariable made on access.

    `md` is the engine's ssx_md (freed with this table); `types` are the SimpleTypes its
    declared_type indices point into. The arrays are read as numpy views, and the objects are
    made a column at a time (one call into the engine per text field, not per variable).
    """

    def __init__(self, md: Any, types: list[SimpleType]) -> None:
        self._md = md
        self._types = types
        self._count = count = int(md.variable_count)
        self._words = words()
        self._name = _column(md.name, count, np.uint32)
        self._value_reference = _column(md.value_reference, count, np.uint32)
        self._description = _column(md.description, count, np.uint32)
        self._unit = _column(md.unit, count, np.uint32)
        self._start = _column(md.start, count, np.uint32)
        self._declared_type = _column(md.declared_type, count, np.int32)
        self._type = _column(md.type, count, np.uint8)
        self._causality = _column(md.causality, count, np.uint8)
        self._variability = _column(md.variability, count, np.uint8)
        self._initial = _column(md.initial, count, np.uint8)
        self._derivative = _column(md.derivative, count, np.uint32)

    def __len__(self) -> int:
        return self._count

    @overload
    def __getitem__(self, index: int) -> ScalarVariable: ...

    @overload
    def __getitem__(self, index: slice) -> list[ScalarVariable]: ...

    def __getitem__(self, index: int | slice) -> ScalarVariable | list[ScalarVariable]:
        if isinstance(index, slice):
            return self.make(np.arange(*index.indices(self._count)))
        if index < 0:
            index += self._count
        if not 0 <= index < self._count:
            raise IndexError(f"variable index {index} out of range (there are {self._count})")
        return self.make(np.array([index]))[0]

    def __iter__(self) -> Iterator[ScalarVariable]:
        for first in range(0, self._count, _BATCH):
            yield from self.make(np.arange(first, min(first + _BATCH, self._count)))

    def names(self) -> Iterator[str]:
        for first in range(0, self._count, _BATCH):
            yield from self._texts(self._name[first:first + _BATCH])  # type: ignore[misc]

    def find(self, name: str) -> int:
        """The index of the variable called `name`, or -1 (a hash lookup in the engine)."""
        return int(lib().ssx_md_find(self._md, name.encode()))

    def duplicates(self) -> dict[str, list[int]]:
        """Each name several variables have, with their value references in document order
        (the engine counts them as it reads, so an FMU without any costs nothing here)."""
        if self._md.duplicate_count == 0:
            return {}
        references: dict[str, list[int]] = {}
        for name, reference in zip(self.names(), self._value_reference.tolist(), strict=True):
            references.setdefault(name, []).append(reference)
        return {name: found for name, found in references.items() if len(found) > 1}

    def derivative_of(self, index: int) -> int:
        """The index of the Real variable declared the time derivative of variable `index`
        (its `derivative` attribute names it), or -1."""
        found = np.flatnonzero(self._derivative == index + 1)
        return int(found[0]) if len(found) else -1

    def with_causality(self, *causalities: str) -> list[ScalarVariable]:
        """The variables of these causalities, in document order."""
        wanted = [self._words.index(causality) for causality in causalities]
        return self.make(np.flatnonzero(np.isin(self._causality, wanted)))

    def by_name(self) -> VariablesByName:
        return VariablesByName(self)

    def make(self, indices: np.ndarray) -> list[ScalarVariable]:
        """The ScalarVariables at these indices."""
        words_, types = self._words, self._types
        return list(map(
            ScalarVariable,
            self._texts(self._name[indices]),
            self._value_reference[indices].tolist(),
            [words_[code] for code in self._type[indices].tolist()],
            [words_[code] for code in self._causality[indices].tolist()],
            [words_[code] for code in self._variability[indices].tolist()],
            [words_[code] or None for code in self._initial[indices].tolist()],
            self._texts(self._description[indices]),
            self._texts(self._unit[indices]),
            [types[k] if k >= 0 else None for k in self._declared_type[indices].tolist()],
            self._texts(self._start[indices])))

    def _texts(self, offsets: np.ndarray) -> list[str | None]:
        """The pool's texts at these offsets (None where 0), read in one pass by the engine."""
        if len(offsets) == 0:
            return []
        offsets = np.ascontiguousarray(offsets, dtype=np.uint32)
        pointer = ffi.from_buffer("uint32_t[]", offsets)
        engine = lib()
        joined = bytearray(engine.ssx_md_join(self._md, pointer, len(offsets), ffi.NULL, 0))
        engine.ssx_md_join(self._md, pointer, len(offsets), ffi.from_buffer(joined), len(joined))
        texts: list[str | None] = list(joined.decode().split("\0"))
        for absent in np.flatnonzero(offsets == 0).tolist():
            texts[absent] = None
        return texts


def _column(pointer: Any, count: int, dtype: type[np.generic]) -> np.ndarray:
    """A read-only numpy view of one of the engine's arrays (empty without variables)."""
    if count == 0:
        return np.empty(0, dtype=dtype)
    size = count * np.dtype(dtype).itemsize
    return np.frombuffer(ffi.buffer(pointer, size), dtype=dtype)


class VariablesByName(Mapping[str, ScalarVariable]):
    """name -> ScalarVariable over a VariableTable, looked up in the engine's name index."""

    def __init__(self, table: VariableTable) -> None:
        self._table = table

    def __getitem__(self, name: str) -> ScalarVariable:
        index = self._table.find(name) if isinstance(name, str) else -1
        if index < 0:
            raise KeyError(name)
        return self._table[index]

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and self._table.find(name) >= 0

    def __len__(self) -> int:
        return len(self._table)

    def __iter__(self) -> Iterator[str]:
        return self._table.names()
