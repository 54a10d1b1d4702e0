"""An ensemble's results as the workers sent them: a block per task (block.py) and loose
MemberResults (failures, suspects run alone), a Sequence of MemberResult in member order.

A member's MemberResult is cut from its block when first asked for (views, no sample copied):
the client spends nothing per member while the ensemble runs (cutting all 2000 seed members'
results cost it 60 ms, a third of its CPU). The dataset's sample arrays are filled block by
block with numpy (`padded`), and its per-member variables read from the blocks' scalars
(`field`, `statistic`), without a MemberResult per member.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import Any, overload

import numpy as np

from .block import MemberBlock
from .member import STATISTICS, MemberResult
from .members import ParameterSet

# MemberBlock.scalars' fields, by MemberResult's names
SCALAR_FIELDS = ("index", "status", "error", "error_type", "events", "termination",
                 "wall_time")


class MemberList(Sequence[MemberResult]):
    """The results of members 0 .. len(parameters) - 1, `parameters[k]` member k's."""

    def __init__(self, parameters: Sequence[ParameterSet]) -> None:
        self.parameters = parameters
        self._blocks: list[MemberBlock] = []
        self._in_block: dict[int, tuple[int, int]] = {}  # member -> (block, its row there)
        self._loose: dict[int, MemberResult] = {}  # and every member cut from a block

    @classmethod
    def of(cls, results: Sequence[MemberResult]) -> MemberList:
        """A list of results as they are (member k the k-th)."""
        members = cls([result.parameters for result in results])
        members._loose = dict(enumerate(results))
        return members

    def add_block(self, block: MemberBlock) -> list[str]:
        """Keep a task's block; returns its members' statuses."""
        number = len(self._blocks)
        self._blocks.append(block)
        self._in_block.update((scalars[0], (number, row))
                              for row, scalars in enumerate(block.scalars))
        for result in block.others:
            self._loose[result.index] = result
        return [scalars[1] for scalars in block.scalars] + [r.status for r in block.others]

    def add(self, result: MemberResult) -> None:
        self._loose[result.index] = result

    def has(self, index: int) -> bool:
        return index in self._loose or index in self._in_block

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
        result = self._loose.get(index)
        if result is None:
            number, row = self._in_block[index]
            result = self._loose[index] = self._blocks[number].result(row, self.parameters)
        return result

    def __iter__(self) -> Iterator[MemberResult]:
        return (self[k] for k in range(len(self)))

    def field(self, name: str) -> list[Any]:
        """A MemberResult field of every member ("status", "events", "worker"; "samples": its
        count of samples), without cutting members from their blocks."""
        return [self._field(index, name) for index in range(len(self))]

    def statistic(self, name: str) -> list[int]:
        """A run statistic of every member (STATISTICS), -1 where the run did not complete."""
        column = STATISTICS.index(name)
        values = []
        for index in range(len(self)):
            where = self._from_block(index)
            values.append(self[index].statistics.get(name, -1) if where is None
                          else int(self._blocks[where[0]].statistics[where[1], column]))
        return values

    def _from_block(self, index: int) -> tuple[int, int] | None:
        """(block, row) of a member not yet cut from its block, else None."""
        return None if index in self._loose else self._in_block.get(index)

    def _field(self, index: int, name: str) -> Any:
        where = self._from_block(index)
        if where is None:
            member = self[index]
            return member.time.size if name == "samples" else getattr(member, name)
        block, row = self._blocks[where[0]], where[1]
        if name == "samples":
            return int(block.bounds[row + 1] - block.bounds[row])
        if name == "worker":
            return block.worker
        return block.scalars[row][SCALAR_FIELDS.index(name)]

    def output_names(self) -> list[str]:
        """Every "Component.port" recorded by some member, in first-seen order."""
        names: dict[str, None] = {}
        for index in range(len(self)):
            where = self._from_block(index)
            member_names = tuple(self[index].outputs) if where is None \
                else self._blocks[where[0]].names
            names.update(dict.fromkeys(member_names))
        return list(names)

    def padded(self, names: Sequence[str]) -> tuple[np.ndarray, np.ndarray,
                                                    dict[str, np.ndarray]]:
        """time, micro and each output as member x sample arrays, the shorter members padded
        with NaN (micro -1)."""
        sizes = self.field("samples")
        shape = (len(self), max(sizes, default=0))
        time, micro = np.full(shape, np.nan), np.full(shape, -1, dtype=np.int64)
        outputs = {name: np.full(shape, np.nan) for name in names}
        for number, block in enumerate(self._blocks):
            rows = [row for row, scalars in enumerate(block.scalars)
                    if self._from_block(scalars[0]) == (number, row)]
            if not rows:
                continue
            # every sample of those rows: its member and its position in the member's samples
            starts, counts = block.bounds[rows], np.diff(block.bounds)[rows]
            picked = np.arange(block.bounds[-1]) if len(rows) == len(block.scalars) else \
                np.concatenate([np.arange(s, s + c) for s, c in zip(starts, counts, strict=True)])
            members = np.repeat([block.scalars[row][0] for row in rows], counts)
            positions = picked - np.repeat(starts, counts)
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
