"""A dict whose array parts are made when asked for.

An FMI 3.0 array `a` of shape (2, 3) stands for the names `a[0,0]`, ..., `a[1,2]` (row-major,
0-based: FMPy's names). A port, a spec, a start value or a value reference per element would
make an FMU with a 10**5-element array cost seconds and a hundred MB to open, so an ElementMap
keeps one Block per array (its name, shape and how to make an element's value from its
position) and makes an element's value the first time it is looked up, keeping it from then
on. Everything else behaves as a dict: the values set, in the order of the names (an array's
elements where the array stands).
"""

from __future__ import annotations

import copy
import itertools
import math
from collections.abc import Callable, Iterator, MutableMapping
from typing import Any, NamedTuple, TypeVar

Value = TypeVar("Value")

_ABSENT = object()  # what dict.get answers for a name not made (None may be a value)


class Block(NamedTuple):
    """An array's elements in a map: the name of the array, its shape (() for one value
    under the name itself, made when asked for) and `make(position, name)`, which makes the
    value of the element at row-major `position`. `make` must not depend on anything that
    changes: a copy of the map shares it."""

    name: str
    shape: tuple[int, ...]
    make: Callable[[int, str], Any]

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    def names(self) -> Iterator[str]:
        """The elements' names in row-major order."""
        if not self.shape:
            yield self.name
            return
        for index in itertools.product(*(range(extent) for extent in self.shape)):
            yield f"{self.name}[{','.join(map(str, index))}]"

    def position(self, key: str) -> int | None:
        """The row-major position of the element named `key` (FMPy's spelling, no spaces),
        None when `key` names none of this block's elements."""
        if not self.shape:
            return 0 if key == self.name else None
        if not (key.startswith(self.name) and key[len(self.name):][:1] == "["
                and key.endswith("]")):
            return None
        texts = key[len(self.name) + 1:-1].split(",")
        if len(texts) != len(self.shape) or not all(
                t.isascii() and t.isdigit() and (t == "0" or t[0] != "0") for t in texts):
            return None
        position = 0
        for text, extent in zip(texts, self.shape, strict=True):
            index = int(text)
            if index >= extent:
                return None
            position = position * extent + index
        return position


class ElementMap(MutableMapping[str, Value]):
    """A mutable mapping of names to values, some of them made on demand by Blocks."""

    def __init__(self, items: dict[str, Value] | None = None,
                 blocks: list[Block] | None = None) -> None:
        """`items` first, then the names of `blocks`, in their order."""
        self._values: dict[str, Value] = dict(items or {})
        self._order: list[str | Block] = [*self._values, *(blocks or ())]
        self._blocks: dict[str, Block] = {b.name: b for b in blocks or ()}
        self._removed: set[str] = set()
        self._length = len(self._values) + sum(b.size for b in blocks or ())

    @classmethod
    def in_order(cls, parts: list[tuple[str, Any] | Block]) -> ElementMap[Any]:
        """A map of `parts` in their order: (name, value) pairs and Blocks."""
        made: ElementMap[Any] = cls()
        for part in parts:
            if isinstance(part, Block):
                made._order.append(part)
                made._blocks[part.name] = part
                made._length += part.size
            else:
                made._order.append(part[0])
                made._values[part[0]] = part[1]
                made._length += 1
        return made

    def _block_of(self, key: str) -> tuple[Block, int] | None:
        block = self._blocks.get(key.partition("[")[0])
        if block is None or key in self._removed:
            return None
        position = block.position(key)
        return None if position is None else (block, position)

    def _make(self, key: object) -> Any:
        """The element `key` of a Block, made now and kept; _ABSENT where no Block has it."""
        found = self._block_of(key) if isinstance(key, str) else None
        if found is None:
            return _ABSENT
        block, position = found
        value = self._values[key] = block.make(position, key)
        return value

    def __getitem__(self, key: str) -> Value:
        try:
            return self._values[key]
        except KeyError:
            value = self._make(key)
            if value is _ABSENT:
                raise
            return value

    def get(self, key: str, default: Any = None) -> Any:
        # Mapping.get goes through __getitem__ and a KeyError: the made values are a dict
        value = self._values.get(key, _ABSENT)
        if value is _ABSENT:
            value = self._make(key)
        return default if value is _ABSENT else value

    def __contains__(self, key: object) -> bool:
        return key in self._values or (isinstance(key, str) and self._block_of(key) is not None)

    def __setitem__(self, key: str, value: Value) -> None:
        if key not in self._values and key not in self:
            self._order.append(key)
            self._length += 1
        self._values[key] = value

    def __delitem__(self, key: str) -> None:
        if key not in self:
            raise KeyError(key)
        self._values.pop(key, None)
        if self._block_of(key) is not None:
            self._removed.add(key)
        else:
            self._order.remove(key)
        self._length -= 1

    def __iter__(self) -> Iterator[str]:
        for entry in self._order:
            if isinstance(entry, str):
                yield entry
            elif self._removed:
                yield from (n for n in entry.names() if n not in self._removed)
            else:
                yield from entry.names()

    def __len__(self) -> int:
        return self._length

    def __repr__(self) -> str:
        made = len(self._values)
        return f"ElementMap({len(self)} names, {made} made)"

    def made(self) -> dict[str, Value]:
        """The values made or set so far (a Block's elements not yet asked for are not)."""
        return self._values

    def copy(self) -> ElementMap[Value]:
        """A map of its own with the same names and values (the Blocks shared)."""
        twin: ElementMap[Value] = ElementMap.__new__(ElementMap)
        twin._values = dict(self._values)
        twin._order = list(self._order)
        twin._blocks = self._blocks
        twin._removed = set(self._removed)
        twin._length = self._length
        return twin

    def __copy__(self) -> ElementMap[Value]:
        return self.copy()

    def __deepcopy__(self, memo: dict[int, Any]) -> ElementMap[Value]:
        twin = self.copy()
        twin._values = copy.deepcopy(self._values, memo)
        return twin

    def mapped(self, make: Callable[[str, Value], Any]) -> ElementMap[Any]:
        """A map of the same names whose values are make(name, value), made on demand too."""
        blocks = [Block(b.name, b.shape,
                        lambda position, name, b=b: make(name, self[name]))
                  for b in self._blocks.values()]
        twin: ElementMap[Any] = ElementMap(blocks=blocks)
        twin._order = [e if isinstance(e, str) else twin._blocks[e.name] for e in self._order]
        twin._values = {n: make(n, v) for n, v in self._values.items()}
        twin._removed = set(self._removed)
        twin._length = self._length
        return twin


def made_items(mapping: MutableMapping[str, Value]) -> dict[str, Value]:
    """The values of `mapping` that exist as objects: all of a dict's, the made ones of an
    ElementMap's."""
    return mapping.made() if isinstance(mapping, ElementMap) else dict(mapping)
