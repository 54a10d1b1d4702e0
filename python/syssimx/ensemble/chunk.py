"""What one Dask task of an ensemble runs: consecutive members, described once.

The client sends per task one small object (the members' parameter sets and the experiment
they share), not one MemberTask per member: building, pickling and sending those cost the
client about 40 µs per member (0.08 s of its 0.17 s for 2000 seed members). The worker makes
the MemberTasks itself.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from .block import MemberBlock, run_block
from .member import MemberTask
from .members import ParameterSet
from .system_source import SystemSource


@dataclass(frozen=True)
class Experiment:
    """What every member of an ensemble shares: the run (t0, tf, dt), the outputs kept, the
    run's timeout and the ensemble's name (its members share one System per process)."""

    t0: float
    tf: float
    dt: float
    outputs: tuple[str, ...] | None = None
    timeout: float | None = None
    ensemble: str | None = None

    def task(self, index: int, parameters: ParameterSet, topic: str | None = None
             ) -> MemberTask:
        return MemberTask(index, parameters, self.t0, self.tf, self.dt, self.outputs,
                          self.timeout, topic, self.ensemble)


@dataclass(frozen=True)
class MemberChunk:
    """Members first, first + 1, ... with `parameters`. The members that announce their start
    on `topic`: every one when `announce_each` (the watchdog times each member), else only the
    member of a chunk of one (a worker death is pinned on a chunk of one member only, and each
    announcement costs the worker, the scheduler and the client a message)."""

    first: int
    parameters: Sequence[ParameterSet]
    experiment: Experiment
    topic: str | None = None
    announce_each: bool = False

    def __len__(self) -> int:
        return len(self.parameters)

    @property
    def indices(self) -> range:
        return range(self.first, self.first + len(self.parameters))

    def tasks(self) -> list[MemberTask]:
        topic = self.topic if self.announced else None
        return [self.experiment.task(self.first + offset, values, topic)
                for offset, values in enumerate(self.parameters)]

    @property
    def announced(self) -> bool:
        """Whether its members announce their start."""
        return self.topic is not None and (self.announce_each or len(self.parameters) == 1)


def run_chunk(build: SystemSource, chunk: MemberChunk) -> MemberBlock:
    """The Dask task: run the chunk's members here, one block of results back."""
    return run_block(build, chunk.tasks())
