"""An ensemble's results as the workers sent them: a block per task (block.py) and loose
MemberResults (failures, suspects run alone), a Sequence of MemberResult in member order.

The client keeps the blocks as they came: adding one is a few numpy assignments, whatever its
members. A member's MemberResult is cut from its block when first asked for (views, no sample
copied). What the dataset needs of every member (`padded` samples, `events`, `text` fields,
`numbers`, `statistic`) is read from the blocks' arrays with numpy, without a MemberResult or
any other Python object per member (cutting all 2000 seed members' results cost the client
60 ms, a third of its CPU, before).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from typing import Any, overload

import numpy as np

from .block import TEXT_FIELDS, MemberBlock
from .member import STATISTICS, MemberResult
from .members import ParameterTable


class MemberList(Sequence[MemberResult]):
    """The results of members 0 .. len(parameters) - 1, `parameters[k]` member k's."""

    def __init__(self, parameters: ParameterTable) -> None:
        self.parameters = parameters
        self._blocks: list[MemberBlock] = []
        self._block = np.full(len(parameters), -1, dtype=np.int64)  # -1: in no block
        self._row = np.zeros(len(parameters), dtype=np.int64)  # its row in its block
        self._loose: dict[int, MemberResult] = {}  # the results of members in no block
        self._cut: dict[int, MemberResult] = {}  # the members cut from their block so far

    @classmethod
    def of(cls, results: Sequence[MemberResult]) -> MemberList:
        """A list of results as they are (member k the k-th)."""
        members = cls(ParameterTable.of([result.parameters for result in results]))
        members._loose = dict(enumerate(results))
        return members

    def add_block(self, block: MemberBlock) -> tuple[int, int]:
        """Keep a task's block; returns how many members it has, and how many failed."""
        self._block[block.indices] = len(self._blocks)
        self._row[block.indices] = np.arange(len(block.indices))
        self._blocks.append(block)
        for result in block.others:
            self.add(result)
        ok = block.texts.index("ok") if "ok" in block.texts else -1
        failed = np.count_nonzero(block.codes[:, TEXT_FIELDS.index("status")] != ok)
        return len(block), int(failed) + sum(not result.ok for result in block.others)

    def add(self, result: MemberResult) -> None:
        self._loose[result.index] = result
        self._block[result.index] = -1

    def has(self, index: int) -> bool:
        return index in self._loose or self._block[index] >= 0

    def __len__(self) -> int:
        return len(self.parameters)

    @overload
    def __getitem__(self, index: int) -> MemberResult: ...

    @overload
    def __getitem__(self, index: slice) -> list[MemberResult]: ...

    def __getitem__(self, index: int | slice) -> MemberResult | list[MemberResult]:
        if isinstance(index, slice):
            return [self[k] for k in range(*index.indices(len(self)))]
        if index < 0:
            index += len(self)
        if not 0 <= index < len(self):
            raise IndexError(f"member {index} of {len(self)}")
        result = self._loose.get(index) or self._cut.get(index)
        if result is None:
            block = self._blocks[self._block[index]]
            result = self._cut[index] = block.result(int(self._row[index]), self.parameters)
        return result

    def __iter__(self) -> Iterator[MemberResult]:
        return (self[k] for k in range(len(self)))

    def text(self, name: str) -> np.ndarray:
        """A string field of every member ("status", "error", "error_type", "termination",
        "worker"), as an array of objects."""
        def of_block(block: MemberBlock, rows: np.ndarray) -> Any:
            if name == "worker":
                return block.worker
            return np.array(block.texts, dtype=object)[block.codes[rows,
                                                                   TEXT_FIELDS.index(name)]]

        return self._collect(np.full(len(self), "", dtype=object), of_block,
                             lambda result: getattr(result, name))

    def numbers(self, name: str) -> np.ndarray:
        """Every member's "wall_time" (float64) or count of "samples" (int64)."""
        if name == "wall_time":
            return self._collect(np.full(len(self), np.nan),
                                 lambda block, rows: block.wall_time[rows],
                                 lambda result: result.wall_time)
        return self._collect(np.zeros(len(self), dtype=np.int64),
                             lambda block, rows: np.diff(block.bounds)[rows],
                             lambda result: result.time.size)

    def statistic(self, name: str) -> np.ndarray:
        """A run statistic of every member (STATISTICS), -1 where the run did not complete."""
        column = STATISTICS.index(name)
        return self._collect(np.full(len(self), -1, dtype=np.int64),
                             lambda block, rows: block.statistics[rows, column],
                             lambda result: result.statistics.get(name, -1))

    def _collect(self, values: np.ndarray, of_block: Callable[[MemberBlock, np.ndarray], Any],
                 of_result: Callable[[MemberResult], Any]) -> np.ndarray:
        """`values` filled per member: from its block's rows, or from its loose result."""
        for block, rows in self._rows():
            values[block.indices[rows]] = of_block(block, rows)
        for index, result in self._loose.items():
            values[index] = of_result(result)
        return values

    def _rows(self) -> Iterator[tuple[MemberBlock, np.ndarray]]:
        """Each block with the rows of its members that are still its (a member run again
        alone, after its block came, is loose)."""
        for number, block in enumerate(self._blocks):
            rows = np.flatnonzero(self._block[block.indices] == number)
            if rows.size:
                yield block, rows

    def output_names(self) -> list[str]:
        """Every "Component.port" recorded by some member, in first-seen order (by member)."""
        sources = [(int(block.indices[rows[0]]), block.names) for block, rows in self._rows()]
        sources += [(index, tuple(result.outputs)) for index, result in self._loose.items()]
        names: dict[str, None] = {}
        for _, member_names in sorted(sources, key=lambda source: source[0]):
            names.update(dict.fromkeys(member_names))
        return list(names)

    def padded(self, names: Sequence[str]) -> tuple[np.ndarray, np.ndarray,
                                                    dict[str, np.ndarray]]:
        """time, micro and each output as member x sample arrays, the shorter members padded
        with NaN (micro -1)."""
        sizes = self.numbers("samples")
        shape = (len(self), int(sizes.max(initial=0)))
        time, micro = np.full(shape, np.nan), np.full(shape, -1, dtype=np.int64)
        outputs = {name: np.full(shape, np.nan) for name in names}
        for block, rows in self._rows():
            picked, members, positions = _spread(block.bounds, rows, block.indices)
            time[members, positions] = block.samples[picked, 0]
            micro[members, positions] = block.micro[picked]
            for column, name in enumerate(block.names, start=1):
                outputs[name][members, positions] = block.samples[picked, column]
        for index, member in self._loose.items():
            n = member.time.size
            time[index, :n], micro[index, :n] = member.time, member.micro
            for name, values in member.outputs.items():
                outputs[name][index, :n] = values
        return time, micro, outputs

    def events(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Every member's events as member x event arrays: time (NaN past a member's last),
        micro (-1) and source ("Component.event", "" past the last, as objects)."""
        counts = self._collect(np.zeros(len(self), dtype=np.int64),
                               lambda block, rows: np.diff(block.event_bounds)[rows],
                               lambda result: len(result.events))
        shape = (len(self), int(counts.max(initial=0)))
        time, micro = np.full(shape, np.nan), np.full(shape, -1, dtype=np.int64)
        source = np.full(shape, "", dtype=object)
        for block, rows in self._rows():
            picked, members, positions = _spread(block.event_bounds, rows, block.indices)
            time[members, positions] = block.event_time[picked]
            micro[members, positions] = block.event_micro[picked]
            source[members, positions] = np.array(block.texts, dtype=object)[
                block.event_source[picked]]
        for index, member in self._loose.items():
            for column, (t, step, name) in enumerate(member.events):
                time[index, column], micro[index, column], source[index, column] = t, step, name
        return time, micro, source


def _spread(bounds: np.ndarray, rows: np.ndarray, indices: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For the items of a block's `rows` (row k's items are bounds[k]:bounds[k + 1]): each
    item's position in the block, its member (from `indices`) and its position among the
    member's items."""
    starts, counts = bounds[rows], np.diff(bounds)[rows]
    picked = np.arange(bounds[-1]) if rows.size == len(bounds) - 1 else \
        np.concatenate([np.arange(s, s + c) for s, c in zip(starts, counts, strict=True)])
    return picked, np.repeat(indices[rows], counts), picked - np.repeat(starts, counts)
