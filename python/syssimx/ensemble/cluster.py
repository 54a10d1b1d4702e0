"""The Dask client an ensemble runs on: the caller's, a scheduler's address, or an embedded
LocalCluster of worker processes (one per core, one member at a time each) started for the
ensemble and closed after it."""

from __future__ import annotations

import gc
import logging
import os
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from ..errors import ConfigurationError
from .deferred_interrupt import interrupts_deferred

# The embedded cluster fails the tasks of a worker that died at once instead of retrying them
# on another worker (a crashing member would crash that one too; runner.py sorts the crashed
# member from the innocent ones), and keeps one task queued on each worker besides the one it
# runs: the next starts without waiting for the scheduler, and a crash takes at most one
# innocent task with it. The workers' statistical profiler is off: it samples the running
# thread every 10 ms and made Python-heavy members (building a System) about twice as slow.
# Dask's housekeeping is slowed or left out where it serves what an ensemble does not use, as
# it costs the client's process (scheduler, nannies, client) CPU every second, whether members
# run or not, and more with each worker (measured on the 2-core VM with two workers, idle:
# 12.8 -> 5.0 ms of CPU per second, with the heartbeats below):
# - every process's event-loop tick (a check for a blocked loop, every 20 ms) every second;
# - the system monitor (the dashboard's figures; the cluster has no dashboard) every 10 s;
# - the memory monitor of each nanny every second, not 0.5 s (a nanny still ends a worker past
#   its memory limit, within a second);
# - no active memory manager: it drops extra copies of data the workers hold, and an
#   ensemble's workers hold none (each task's block is fetched once and released);
# - the client's copy of the scheduler's description (its repr) every 30 s, not 2 s: what the
#   ensemble asks of the scheduler it asks when it needs it.
# On Linux the worker processes are forked from this one instead of spawned: a spawned worker
# imports Python, numpy, distributed and syssimx again, and the first member in it loads what
# its System needs (pint alone: 2.5 s); a forked one starts with all of this process has
# loaded. Measured on the 2-core VM (benchmarks/ensemble_end_to_end.py): the cluster's start
# 6 s -> 0.3 s, its close 2.2 s -> 0.15 s. A forked worker shares its parent's FMU extraction
# folders without owning them (fmu/extraction.py).
WORKER_START_METHOD = "fork" if sys.platform == "linux" else "spawn"
START_METHOD = "distributed.worker.multiprocessing-method"
EMBEDDED_SCHEDULER_CONFIG = {
    "distributed.scheduler.allowed-failures": 0,
    "distributed.scheduler.worker-saturation": 2.0,
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.system-monitor.interval": "10s",
    "distributed.worker.memory.monitor-interval": "1s",
    "distributed.scheduler.active-memory-manager.start": False,
    "distributed.client.scheduler-info-interval": "30s",
}
# A worker's heartbeat tells the scheduler its metrics for the dashboard and that it is alive;
# Dask asks for one every 0.5 s up to 10 workers, each a message through the scheduler (the
# client's process): 3-4 ms of its CPU per second with two workers. A dead worker is found
# by its nanny (the process ends) and its closed connection, not by a missed heartbeat, and
# the scheduler waits 5 minutes (distributed.scheduler.worker-ttl) before it counts one as
# missed. The embedded cluster asks every HEARTBEAT seconds instead; the cluster's own record
# of itself kept on the scheduler (for tools that reconnect to a cluster by name) is sent
# every CLUSTER_SYNC seconds, not every second.
HEARTBEAT = 5.0
CLUSTER_SYNC = 30.0


# Every socket of the embedded cluster (scheduler, workers, nannies, the scheduler's HTTP
# server) listens on loopback only, at a port the system picks. It has no dashboard: the
# cluster lives for one sweep and nobody is told its address, and a dashboard shows the
# workers, their memory and local folders to anyone who reaches it. A cluster of the user's
# own (client=, scheduler=) is theirs to expose.
LOOPBACK = "127.0.0.1"


def cores() -> int:
    """The cores this process may run on."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") \
        else os.cpu_count() or 1


def check_processes(client: Any) -> int:
    """Members run in processes, never side by side in threads of one process (FMU binaries
    are native code, and many are not thread-safe): every worker must have one thread.
    Returns the number of workers."""
    nthreads = client.nthreads()
    threaded = {worker: n for worker, n in nthreads.items() if n != 1}
    if threaded:
        raise ConfigurationError(f"ensemble workers must run one thread each (start them with "
                                 f"'dask worker ADDRESS --nthreads 1'); threads per worker: "
                                 f"{threaded}")
    return len(nthreads)


@contextmanager
def ensemble_client(client: Any = None, scheduler: str | None = None,
                    workers: int | None = None) -> Iterator[Any]:
    """`client` as given; else a Client of `scheduler` (e.g. "tcp://host:8786"); else an
    embedded LocalCluster of `workers` processes (default: one per core)."""
    if client is not None:
        yield client
        return
    import dask
    from distributed import Client, LocalCluster

    if scheduler is not None:
        with Client(scheduler) as remote:
            yield remote
        return
    count = cores() if workers is None else workers
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise ConfigurationError(f"workers must be a positive integer, got {workers!r}")
    # The workers' stream handlers are silenced; their nannies still keep the INFO lines
    # (how a worker died) that a crashed member's reason is read from. Ctrl-C while the
    # cluster starts or closes comes once it is whole, so that it is closed entirely.
    cluster = local = None
    try:
        # the start method for the cluster's life (a nanny reads it again to restart a worker
        # after a crash); the rest is read as the cluster and the client are made, and set
        # only meanwhile: a cluster the user makes beside it keeps the user's settings
        with dask.config.set({START_METHOD: WORKER_START_METHOD}):
            with dask.config.set(EMBEDDED_SCHEDULER_CONFIG), interrupts_deferred(), \
                    _frozen_for_the_fork():
                cluster = LocalCluster(n_workers=count, threads_per_worker=1, processes=True,
                                       host=LOOPBACK, dashboard_address=f"{LOOPBACK}:0",
                                       scheduler_kwargs={"dashboard": False},
                                       silence_logs=logging.CRITICAL,
                                       scheduler_sync_interval=CLUSTER_SYNC,
                                       heartbeat_interval=HEARTBEAT)
                _slow_heartbeats(cluster.scheduler)
                local = Client(cluster)
            yield local
    finally:
        with interrupts_deferred():
            if local is not None:
                local.close()
            if cluster is not None:
                cluster.close()
            # a worker killed by a signal (a member's crash, the nanny's SIGTERM) left its FMU
            # extractions: their owner is gone now
            import tempfile
            from pathlib import Path

            from ..fmu.extraction import remove_stale_folders

            remove_stale_folders(Path(tempfile.gettempdir()))


def _slow_heartbeats(scheduler: Any) -> None:
    """The workers of `scheduler` (in this process) told to come back every HEARTBEAT seconds
    at the least: the worker sets its next heartbeat from the scheduler's reply to the last
    (its first comes HEARTBEAT seconds after its start, the interval it was started with)."""
    handler = scheduler.handlers.get("heartbeat_worker")
    if handler is None:  # a Dask that names it otherwise: Dask's interval, at its cost
        return

    def heartbeat_worker(**message: Any) -> Any:
        reply = handler(**message)
        if isinstance(reply, dict) and "heartbeat-interval" in reply:
            reply["heartbeat-interval"] = max(reply["heartbeat-interval"], HEARTBEAT)
        return reply

    scheduler.handlers["heartbeat_worker"] = heartbeat_worker


@contextmanager
def _frozen_for_the_fork() -> Iterator[None]:
    """This process's objects moved out of the garbage collector's reach while the workers
    fork, and back after: a forked worker keeps them out of reach, so that its collections
    neither walk them (about 90 000 objects once syssimx and distributed are loaded) nor
    write to their pages, which the fork shares with this process until written (4 500 of a
    worker's 6 200 page faults in its first 2000 seed members on the 2-core VM). Left alone
    where the user froze objects already: unfreezing would release theirs."""
    if WORKER_START_METHOD != "fork" or gc.get_freeze_count():
        yield
        return
    gc.freeze()
    try:
        yield
    finally:
        gc.unfreeze()
