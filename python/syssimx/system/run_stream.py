"""A run streamed to disk (System.run(stream_to=...)): a block writer attached to the engine
for the run, handed the samples the history keeps, detached when the run returns."""

from __future__ import annotations

from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np

from ..atomic_file import is_special
from ..bridge.observers import add_block_writer, columns, remove_observer
from ..bridge.plan import EnginePlan
from ..errors import ConfigurationError


class RunStream:
    """stream_to: a path (its suffix chooses the format; the file is written whole by this run
    and closed) or a writer object of yours (started once, written by every run it is given,
    closed by you)."""

    def __init__(self, plan: EnginePlan, stream_to: Any, t0: float, started: set[int]) -> None:
        if isinstance(stream_to, str | Path):
            from ..streaming import open_writer

            try:
                self.writer = open_writer(stream_to)
            except ValueError as exc:
                raise ConfigurationError(str(exc)) from None
            self.owned = True
            _refuse_seeking_into_a_stream(Path(stream_to))
            names = columns(plan)
            _refuse_repeated(names, stream_to)
            try:
                self.writer.open(Path(stream_to), names)
            except OSError as exc:  # a folder, a missing folder, no permission
                raise ConfigurationError(f"cannot stream a run to {stream_to}: "
                                         f"{exc.strerror or exc}") from exc
        elif callable(getattr(stream_to, "write", None)):
            self.writer = stream_to
            self.owned = False
        else:
            raise ConfigurationError(f"stream_to must be a path or an object with write(t, micro, "
                                     f"values), got {stream_to!r}")
        self.plan = plan
        first = self.owned or id(stream_to) not in started
        if not self.owned and first:
            started.add(id(stream_to))
            if callable(getattr(stream_to, "start", None)):
                stream_to.start(columns(plan))
        if first:
            self._write_start_point(t0)
        self.observer = add_block_writer(plan, self.writer.write)

    def _write_start_point(self, t0: float) -> None:
        """The samples at t0 the history holds already (the state the run starts from, and the
        instants of an event there): the file starts where the run does."""
        history = self.plan.history()
        if history.length == 0:
            return
        time, micro = history.time(), history.micro()
        rows = np.flatnonzero(time == t0)
        if len(rows) == 0:
            return
        parts = [history.values(index, len(self.plan.outputs[name]))[rows]
                 for name, index in self.plan.index.items() if self.plan.outputs[name]]
        values = np.hstack(parts) if parts else np.empty((len(rows), 0))
        self.writer.write(time[rows], micro[rows], values)

    def finish(self) -> None:
        """Detach from the engine; a path's file is closed (complete on disk)."""
        remove_observer(self.plan, self.observer)
        if self.owned:
            self.writer.close()


def _refuse_seeking_into_a_stream(target: Path) -> None:
    """NetCDF and Parquet writers seek back (a record count, a footer's offsets): a FIFO or a
    device cannot take that, and the run's samples would be lost after it is computed."""
    if target.suffix.lower() != ".csv" and is_special(target):
        raise ConfigurationError(f"cannot stream a run to {target}: a {target.suffix} file is "
                                 "written with seeks, which a FIFO or a device cannot take; "
                                 "stream CSV there, or write the result afterwards")


def _refuse_repeated(names: list[str], target: Any) -> None:
    """Column names are component.output: a component "a.b" with an output "c" and a component
    "a" with an output "b.c" both give "a.b.c", which no file format holds twice."""
    repeated = sorted(name for name, count in Counter(names).items() if count > 1)
    if repeated:
        raise ConfigurationError(f"cannot stream a run to {target}: the columns "
                                 f"{', '.join(map(repr, repeated))} would each be written twice "
                                 "(component.output names that coincide); rename a component")
