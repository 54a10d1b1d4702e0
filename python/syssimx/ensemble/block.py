"""The results of one Dask task's members as one compact block: what a worker sends back.

Per-member Python objects (a MemberResult with its own arrays and dicts each) cost the client
and the worker a pickle, a message part and an unpickle per member. A block carries the
samples of all its members stacked in one float64 array (time, then the outputs, as columns)
with one micro array, the statistics as one integer array, and per member only its few
scalars. The client cuts MemberResults out of it as views, without copying a sample.

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

# per member: index, status, error, error_type, events, termination, wall_time
Scalars = tuple[int, str, str, str, tuple[tuple[float, int, str], ...], str, float]


@dataclass(frozen=True)
class MemberBlock:
    """`samples[bounds[k]:bounds[k + 1]]` are the k-th member's (of `scalars`) samples."""

    worker: str
    names: tuple[str, ...]
    scalars: tuple[Scalars, ...]
    samples: np.ndarray  # samples x (1 + len(names)): time, then each output
    micro: np.ndarray
    bounds: np.ndarray
    statistics: np.ndarray  # members x len(STATISTICS); -1: the run did not complete
    others: tuple[MemberResult, ...] = ()
    # CPU seconds per member after the first (which may have built the System); None: one
    # member. CPU, not wall: on a loaded machine a member's wall time grows with the load.
    cost: float | None = None

    def __len__(self) -> int:
        return len(self.scalars) + len(self.others)

    def results(self, parameters: Mapping[int, ParameterSet] | Sequence[ParameterSet]
                ) -> list[MemberResult]:
        """The members' results, their parameters from `parameters` (by member index)."""
        return [*self.others, *(self.result(row, parameters) for row in range(len(self.scalars)))]

    def result(self, row: int, parameters: Mapping[int, ParameterSet] | Sequence[ParameterSet]
               ) -> MemberResult:
        """The MemberResult of the member of `scalars[row]`, its samples views of the block's."""
        index, status, error, error_type, events, termination, wall = self.scalars[row]
        rows = slice(int(self.bounds[row]), int(self.bounds[row + 1]))
        block = self.samples[rows]
        return MemberResult(
            index, parameters[index], status, error, error_type, block[:, 0], self.micro[rows],
            {name: block[:, column] for column, name in enumerate(self.names, start=1)}, events,
            {name: int(v) for name, v in zip(STATISTICS, self.statistics[row], strict=True)
             if v >= 0}, termination, wall, self.worker)


def pack(results: Sequence[MemberResult], cost: float | None = None) -> MemberBlock:
    """One block of `results` (members of one task, run in one process)."""
    worker = results[0].worker if results else ""
    names = next((tuple(r.outputs) for r in results if r.outputs), ())
    regular = [r for r in results if tuple(r.outputs) == names
               and all(series.size == r.time.size for series in r.outputs.values())]
    kept = {id(r) for r in regular}
    others = tuple(r for r in results if id(r) not in kept)
    sizes = [r.time.size for r in regular]
    bounds = np.zeros(len(regular) + 1, dtype=np.int64)
    np.cumsum(sizes, out=bounds[1:])
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
    scalars = tuple((r.index, r.status, r.error, r.error_type, r.events, r.termination,
                     r.wall_time) for r in regular)
    return MemberBlock(worker, names, scalars, samples, micro, bounds, statistics, others, cost)


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
