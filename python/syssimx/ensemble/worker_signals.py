"""Extraction folders of a sweep's worker processes, removed when a worker gets SIGTERM or
SIGHUP (a nanny's kill, a closed terminal, a batch system's stop).

A process's first extraction sets the handlers that remove its folders on those signals
(fmu/extraction.py), but only on the main thread, where Python allows signal handlers, and a
member runs on a worker's executor thread. A worker plugin's setup runs on the worker's event
loop, which in a worker process of its own (a nanny's child, `dask worker`) is the main
thread: the plugin sets the handlers there, for every worker the cluster has or starts later.
"""

from __future__ import annotations

import weakref
from typing import Any

from distributed.diagnostics.plugin import WorkerPlugin

from ..fmu.extraction import remove_extractions_on_signals

# the clients whose cluster has the plugin: registering it again (a round trip to the scheduler,
# 2-3 ms of the client's CPU on the 2-core VM) is left to the first sweep on each client
_REGISTERED: weakref.WeakSet[Any] = weakref.WeakSet()


def register(client: Any) -> None:
    """ExtractionsRemovedOnSignals on the cluster of `client`: its workers, and those it starts
    later (the scheduler keeps the plugin for them)."""
    if client not in _REGISTERED:
        client.register_plugin(ExtractionsRemovedOnSignals())
        _REGISTERED.add(client)


class ExtractionsRemovedOnSignals(WorkerPlugin):
    """Sets the extraction folders' SIGTERM and SIGHUP handlers in each worker process."""

    name = "syssimx-extractions-removed-on-signals"
    idempotent = True  # once per cluster is enough (several clients may share one)

    def setup(self, worker: Any) -> None:
        remove_extractions_on_signals()
