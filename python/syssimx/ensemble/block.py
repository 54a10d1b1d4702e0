"""The results of one Dask task's members as one compact block: what a worker sends back.

Per-member Python objects (a MemberResult with its own arrays and dicts each) cost the client
and the worker a pickle, a message part and an unpickle per member. A block carries the
samples of all its members stacked in one float64 array (time, then the outputs, as columns)
with one micro array, the statistics as one integer array, the events one after another in
three arrays, and the members' strings (status, error, termination, event sources) as integer
codes into one tuple of the distinct strings: the client receives a few arrays per task,
whatever its members, and keeps them (member_list.py); it cuts a MemberResult out of a block
as views, without copying a sample, only when asked for one.

A member whose outputs are not the block's (one that failed before it recorded anything)
travels as its own MemberResult.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from .leftovers import end_left_children
from .member import STATISTICS, MemberResult, MemberTask, run_member
from .members import ParameterSet
from .system_source import SystemSource

# a member's strings, as columns of MemberBlock.codes
TEXT_FIELDS = ("status", "error", "error_type", "termination")


@dataclass(frozen=True)
class MemberBlock:
    """The k-th member of the block (member `indices[k]` of the ensemble) has the samples
    `samples[bounds[k]:bounds[k + 1]]`, the events `event_*[event_bounds[k]:event_bounds[k +
    1]]`, and its strings (TEXT_FIELDS) and events' sources as codes into `texts`: every field
    of every member in a few arrays, no Python object per member."""

    worker: str
    names: tuple[str, ...]
    indices: np.ndarray  # int64, one per member
    texts: tuple[str, ...]  # the distinct strings the codes name
    codes: np.ndarray  # int32, members x len(TEXT_FIELDS)
    wall_time: np.ndarray  # float64, one per member
    samples: np.ndarray  # samples x (1 + len(names)): time, then each output
    micro: np.ndarray
    bounds: np.ndarray
    statistics: np.ndarray  # members x len(STATISTICS); -1: the run did not complete
    event_time: np.ndarray  # float64, the members' events one after another
    event_micro: np.ndarray  # int64
    event_source: np.ndarray  # int32 codes into texts ("Component.event")
    event_bounds: np.ndarray  # int64, members + 1
    others: tuple[MemberResult, ...] = ()
    # CPU seconds per member after the first (which may have built the System); None: one
    # member. CPU, not wall: on a loaded machine a member's wall time grows with the load.
    cost: float | None = None

    def __len__(self) -> int:
        return len(self.indices) + len(self.others)

    def text(self, row: int, field: str) -> str:
        return self.texts[int(self.codes[row, TEXT_FIELDS.index(field)])]

    def results(self, parameters: Mapping[int, ParameterSet] | Sequence[ParameterSet]
                ) -> list[MemberResult]:
        """The members' results, their parameters from `parameters` (by member index)."""
        return [*self.others, *(self.result(row, parameters) for row in range(len(self.indices)))]

    def result(self, row: int, parameters: Mapping[int, ParameterSet] | Sequence[ParameterSet]
               ) -> MemberResult:
        """The MemberResult of the block's `row`-th member, its samples views of the block's."""
        index = int(self.indices[row])
        rows = slice(int(self.bounds[row]), int(self.bounds[row + 1]))
        block = self.samples[rows]
        events = slice(int(self.event_bounds[row]), int(self.event_bounds[row + 1]))
        return MemberResult(
            index, parameters[index], *(self.text(row, field) for field in TEXT_FIELDS[:3]),
            block[:, 0], self.micro[rows],
            {name: block[:, column] for column, name in enumerate(self.names, start=1)},
            tuple(zip(self.event_time[events].tolist(), self.event_micro[events].tolist(),
                      [self.texts[code] for code in self.event_source[events]], strict=True)),
            {name: int(v) for name, v in zip(STATISTICS, self.statistics[row], strict=True)
             if v >= 0}, self.text(row, "termination"), float(self.wall_time[row]),
            self.worker)


def pack(results: Sequence[MemberResult], cost: float | None = None) -> MemberBlock:
    """One block of `results` (members of one task, run in one process)."""
    worker = results[0].worker if results else ""
    names = next((tuple(r.outputs) for r in results if r.outputs), ())
    regular = [r for r in results if tuple(r.outputs) == names
               and all(series.size == r.time.size for series in r.outputs.values())]
    kept = {id(r) for r in regular}
    others = tuple(r for r in results if id(r) not in kept)
    bounds = _bounds([r.time.size for r in regular])
    samples = np.empty((int(bounds[-1]), 1 + len(names)))
    micro = np.empty(int(bounds[-1]), dtype=np.int64)
    statistics = np.full((len(regular), len(STATISTICS)), -1, dtype=np.int64)
    for k, r in enumerate(regular):
        rows = slice(int(bounds[k]), int(bounds[k + 1]))
        samples[rows, 0] = r.time
        micro[rows] = r.micro
        for column, name in enumerate(names, start=1):
            samples[rows, column] = r.outputs[name]
        for j, name in enumerate(STATISTICS):
            statistics[k, j] = r.statistics.get(name, -1)
    texts: dict[str, int] = {}  # each distinct string once, by its code
    codes = np.array([[texts.setdefault(getattr(r, field), len(texts)) for field in TEXT_FIELDS]
                      for r in regular], dtype=np.int32).reshape(len(regular), len(TEXT_FIELDS))
    events = [event for r in regular for event in r.events]
    sources = np.array([texts.setdefault(source, len(texts)) for _, _, source in events],
                       dtype=np.int32)
    return MemberBlock(
        worker, names, np.array([r.index for r in regular], dtype=np.int64), tuple(texts),
        codes, np.array([r.wall_time for r in regular], dtype=np.float64), samples, micro,
        bounds, statistics, np.array([t for t, _, _ in events], dtype=np.float64),
        np.array([step for _, step, _ in events], dtype=np.int64), sources,
        _bounds([len(r.events) for r in regular]), others, cost)


def _bounds(sizes: Sequence[int]) -> np.ndarray:
    """0, then the running sum of `sizes`."""
    bounds = np.zeros(len(sizes) + 1, dtype=np.int64)
    np.cumsum(sizes, out=bounds[1:])
    return bounds


def run_block(build: SystemSource, tasks: list[MemberTask]) -> MemberBlock:
    """Run members one after another here (one Dask task for several short members), end the
    processes their FMUs forked and left (leftovers.py), and pack their results."""
    end_left_children()  # the first call notes the worker's own children
    results = [run_member(build, task) for task in tasks[:1]]
    cpu = time.thread_time()
    results += [run_member(build, task) for task in tasks[1:]]
    cost = (time.thread_time() - cpu) / (len(tasks) - 1) if len(tasks) > 1 else None
    end_left_children()
    return pack(results, cost)
