"""Numpy arrays over the engine's history buffers, without a copy and without dangling.

Each array holds a reference to the engine buffers it views (ssx_history_retain), released
when the last array over them is collected. While referenced, the engine never moves, writes
or frees those samples: a later run grows into new buffers, a new initialize starts others.
The arrays are read-only, because the same samples are the system's history and every other
reader's; `array.copy()` gives a writable one.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..engine import ffi, lib


class _BufferOwner:
    """The base object of one array: its memory and the engine reference that keeps it."""

    __slots__ = ("__array_interface__", "_block")

    def __init__(self, block: Any, address: int, shape: tuple[int, ...], typestr: str) -> None:
        self._block = block
        self.__array_interface__ = {"data": (address, True), "shape": shape,
                                    "typestr": typestr, "version": 3}


class HistoryArrays:
    """The samples recorded so far by one engine system, as read-only numpy arrays."""

    def __init__(self, sys: Any, release: Any, values: tuple[bytes, ...] = ()) -> None:
        """`release` is ssx_history_release, resolved by the caller before any collection can
        need it (a finalizer must not look up a library function); `values` the system's
        values of String and Binary ports, by number."""
        engine = lib()
        self.length = int(engine.ssx_history_length(sys))
        raw = engine.ssx_history_retain(sys) if self.length > 0 else ffi.NULL
        self._block = ffi.gc(raw, release) if raw != ffi.NULL else None
        # the block's buffers, read now: the arrays need nothing of the system afterwards
        self._time = engine.ssx_history_time(sys)
        self._micro = engine.ssx_history_micro(sys)
        self.values_by_number = values

    @classmethod
    def of_retained(cls, block: Any, length: int, time: Any, micro: Any,
                    release: Any, values: tuple[bytes, ...] = ()) -> HistoryArrays:
        """The arrays of a history reference the caller got (ssx_get_run_outcome) with the
        history's length, times and micro steps: released with the last of them."""
        arrays = cls.__new__(cls)
        arrays.length = length
        arrays._block = ffi.gc(block, release) if block != ffi.NULL else None
        arrays._time, arrays._micro = time, micro
        arrays.values_by_number = values
        return arrays

    def tabled(self, numbers: np.ndarray, kind: str) -> np.ndarray:
        """A String or Binary port's column: the text ("string") or bytes of each number, as
        an object array."""
        # b"" after the values: a table still empty gives the 0 of a port never read a value
        values = [*self.values_by_number, b""]
        if kind == "string":
            values = [value.decode("utf-8", "replace") for value in values]
        column = np.empty(len(values), dtype=object)
        column[:] = values
        return column[numbers.astype(np.intp)]

    def _view(self, pointer: Any, shape: tuple[int, ...], typestr: str) -> np.ndarray:
        if self._block is None or 0 in shape:
            return np.empty(shape, dtype=np.dtype(typestr))
        address = int(ffi.cast("uintptr_t", pointer))
        return np.asarray(_BufferOwner(self._block, address, shape, typestr))

    def time(self) -> np.ndarray:
        return self._view(self._time, (self.length,), "<f8")

    def micro(self) -> np.ndarray:
        return self._view(self._micro, (self.length,), "<i4")

    def values(self, component: int, columns: int) -> np.ndarray:
        """The component's samples x outputs matrix (also after the system is gone)."""
        if self._block is None:
            return np.empty((self.length, columns))
        return self._view(lib().ssx_history_block_values(self._block, component),
                          (self.length, columns), "<f8")
