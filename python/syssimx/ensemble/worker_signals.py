"""Extraction folders of a sweep's worker processes, removed when a worker gets SIGTERM or
SIGHUP (a nanny's kill, a closed terminal, a batch system's stop).

A process's first extraction sets the handlers that remove its folders on those signals
(fmu/extraction.py), but only on the main thread, where Python allows signal handlers, and a
member runs on a worker's executor thread. A worker plugin's setup runs on the worker's event
loop, which in a worker process of its own (a nanny's child, `dask worker`) is the main
thread: the plugin sets the handlers there, for every worker the cluster has or starts later.
"""

from __future__ import annotations

from typing import Any

from distributed.diagnostics.plugin import WorkerPlugin

from ..fmu.extraction import remove_extractions_on_signals


class ExtractionsRemovedOnSignals(WorkerPlugin):
    """Sets the extraction folders' SIGTERM and SIGHUP handlers in each worker process."""

    name = "syssimx-extractions-removed-on-signals"
    idempotent = True  # registered by every sweep: once per cluster is enough

    def setup(self, worker: Any) -> None:
        remove_extractions_on_signals()
