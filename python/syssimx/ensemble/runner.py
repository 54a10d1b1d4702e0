"""Running members as Dask tasks and turning every outcome into a MemberResult.

Short members share a task (chunk_size), so the scheduler's cost per task is paid once for
several, and a task's results come back as one block (block.py). A member's own failures come
back as its result (member.py). Two faults need the client:
- a member still running `member_timeout` (+ KILL_GRACE) seconds after it started is stuck
  where its run's own timeout cannot reach (inside an FMU call): its task is cancelled and its
  worker process restarted (the worker's nanny starts a fresh one);
- a worker process that dies (a segfault in an FMU, an abort, the out-of-memory killer) takes
  down the task it was running and the task queued on it. A task of one member that had
  announced its start on that process is that member's crash, reported with how the process
  died (read from its nanny). Every other member of those tasks is a suspect: each runs again
  alone on the cluster after the batch, where a worker death can only be its own.
Every other member's result is kept and the ensemble finishes.
"""

from __future__ import annotations

import functools
import itertools
import signal
import threading
import time
import uuid
from collections.abc import Sequence
from dataclasses import replace
from typing import Any

from .block import run_block
from .cluster import check_processes
from .member import MemberResult, MemberTask
from .progress import ProgressBar
from .system_source import SystemSource

KILL_GRACE = 1.0  # seconds past member_timeout: the run's own timeout reports first if it can
POLL = 0.1  # seconds between checks for stuck members
DEATH_LOG_WAIT = 10.0  # seconds at most to wait for a nanny to log how its worker died
# members per task at most: a task costs the client and its worker about 4 ms of CPU each
# (scheduling, messages, the result's transfer); a crash reruns its chunk's members alone
MAX_CHUNK = 64
CHUNKS_PER_WORKER = 4  # tasks per worker at least, for the balance


class _Starts:
    """When and where each member started, from the members' announcements."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._starts: dict[int, tuple[float, str, int]] = {}

    def record(self, event: tuple[float, dict[str, Any]]) -> None:
        message = event[1]
        with self._lock:
            self._starts[message["member"]] = (time.monotonic(), message["worker"],
                                               message["pid"])

    def get(self, member: int) -> tuple[float, str, int] | None:
        with self._lock:
            return self._starts.get(member)


def chunk_size(members: int, workers: int) -> int:
    """Members per Dask task: short members share a task, so the per-task cost of the
    scheduler is paid once for several; at least CHUNKS_PER_WORKER tasks per worker keep the
    load balanced."""
    return max(1, min(MAX_CHUNK, members // (CHUNKS_PER_WORKER * max(workers, 1))))


def split(tasks: Sequence[MemberTask], size: int, workers: int, topic: str,
          every_member: bool) -> list[list[MemberTask]]:
    """`tasks` in chunks of `size` at most, as many chunks as a multiple of `workers` and of
    sizes differing by one at most, so no worker is left with a last chunk alone. The members
    that announce their start on `topic`: all when `every_member` (the watchdog times each
    member), else only each chunk's first (a worker death is pinned on a chunk of one member
    only, and each announcement costs the scheduler and the client a message)."""
    count = -(-len(tasks) // size)
    count = min(len(tasks), -(-count // workers) * workers)
    bounds = [len(tasks) * k // count for k in range(count + 1)]
    return [[replace(task, topic=topic) if every_member or offset == 0 else task
             for offset, task in enumerate(tasks[first:last])]
            for first, last in itertools.pairwise(bounds)]


class _Ensemble:
    """The members' tasks on one client, their starts, and the results so far."""

    def __init__(self, client: Any, build: SystemSource, member_timeout: float | None,
                 bar: ProgressBar) -> None:
        self.client, self.build, self.member_timeout, self.bar = client, build, \
            member_timeout, bar
        self.workers = max(1, len(client.nthreads()))
        # one function object for every task: Dask serializes it once, not per task
        self.task = functools.partial(run_block, build)
        self.parameters: dict[int, Any] = {}  # by member index
        self.topic = f"syssimx-ensemble-{uuid.uuid4().hex}"
        self.starts = _Starts()
        self.results: dict[int, MemberResult] = {}
        self._attempt = 0

    def run(self, tasks: Sequence[MemberTask], size: int) -> list[MemberTask]:
        """Run `tasks` in chunks of `size` members; returns the suspects (see the module's
        description). A chunk of one member alone on the cluster (size 0 here: `tasks` is one
        member run alone) makes a worker death that member's."""
        from distributed import as_completed

        alone = size == 0
        self._attempt += 1
        chunks = split(tasks, max(size, 1), self.workers, self.topic,
                       every_member=self.member_timeout is not None)
        futures = self.client.map(
            self.task, chunks,
            key=[f"syssimx-members-{c[0].index}-{self.topic[-8:]}-{self._attempt}"
                 for c in chunks], pure=False)
        by_key = {future.key: chunk for future, chunk in zip(futures, chunks, strict=True)}
        watchdog = _Watchdog(self.client, futures, by_key, self.starts, self.member_timeout) \
            if self.member_timeout is not None else None
        suspects: list[MemberTask] = []
        try:
            for future, outcome in as_completed(futures, with_results=True, raise_errors=False):
                chunk = by_key[future.key]
                if future.status == "finished":
                    self._keep(outcome.results(self.parameters))
                elif future.status == "cancelled":  # the watchdog stopped one of its members
                    assert watchdog is not None
                    self._keep([watchdog.stopped[t.index] for t in chunk
                                if t.index in watchdog.stopped])
                    suspects += [t for t in chunk if t.index not in watchdog.stopped]
                else:
                    suspects += self._failed(future.exception(), chunk, alone)
        finally:
            if watchdog is not None:
                watchdog.close()
            self.client.cancel([future for future in futures if not future.done()])
        return suspects

    def _keep(self, results: Sequence[MemberResult]) -> None:
        for result in results:
            self.results[result.index] = result
            self.bar.advance(not result.ok)

    def _failed(self, error: BaseException, chunk: list[MemberTask], alone: bool
                ) -> list[MemberTask]:
        """Results for a chunk whose task failed; returns its suspects."""
        from distributed.scheduler import KilledWorker

        if not isinstance(error, KilledWorker):
            # the task failed before the members' code ran (e.g. the function did not unpickle)
            self._keep([MemberResult(t.index, t.parameters, "failed",
                                     f"{type(error).__name__}: {error}", type(error).__name__)
                        for t in chunk])
            return []
        dead = error.last_worker
        start = self.starts.get(chunk[0].index)
        # one member that announced its start on the dead process: nobody else was running
        if alone or (len(chunk) == 1 and start is not None and start[2] == dead.pid):
            task = chunk[0]
            # the process the member announced its start from: the scheduler's record of the
            # dead worker can name the process that ran there before a restart
            pid = start[2] if start is not None else dead.pid
            reason = (f"WorkerDied: the worker process {pid} ({dead.address}) died while "
                      f"running this member{_death(self.client, pid)}")
            self._keep([MemberResult(task.index, task.parameters, "failed", reason,
                                     "WorkerDied")])
            return []
        return list(chunk)


def run_members(client: Any, build: SystemSource, tasks: Sequence[MemberTask],
                member_timeout: float | None, progress: bool) -> list[MemberResult]:
    """Every member's result, in member order."""
    from .worker_signals import ExtractionsRemovedOnSignals

    check_processes(client)
    client.register_plugin(ExtractionsRemovedOnSignals())
    bar = ProgressBar(len(tasks), progress)
    ensemble = _Ensemble(client, build, member_timeout, bar)
    ensemble.parameters = {task.index: task.parameters for task in tasks}
    client.subscribe_topic(ensemble.topic, ensemble.starts.record)
    try:
        for suspect in ensemble.run(tasks, chunk_size(len(tasks), ensemble.workers)):
            ensemble.run([suspect], 0)
    except KeyboardInterrupt as stop:  # Ctrl-C: the finished members are kept
        raise MembersInterrupted([ensemble.results.get(task.index) or MemberResult(
            task.index, task.parameters, "failed", "interrupted (Ctrl-C) before it finished",
            "KeyboardInterrupt") for task in tasks]) from stop
    finally:
        bar.close()
        client.unsubscribe_topic(ensemble.topic)
    return [ensemble.results[task.index] for task in tasks]


class MembersInterrupted(KeyboardInterrupt):
    """Ctrl-C during run_members: every member's result, the unfinished ones failed."""

    def __init__(self, results: list[MemberResult]) -> None:
        super().__init__("interrupted")
        self.results = results


class _Watchdog(threading.Thread):
    """Stops members running past member_timeout + KILL_GRACE: cancels their task (so it is
    not run again) and restarts its worker process."""

    def __init__(self, client: Any, futures: Sequence[Any],
                 by_key: dict[Any, list[MemberTask]], starts: _Starts,
                 member_timeout: float) -> None:
        super().__init__(name="syssimx-ensemble-watchdog", daemon=True)
        self.client, self.futures, self.by_key = client, futures, by_key
        self.starts, self.member_timeout = starts, member_timeout
        self.stopped: dict[int, MemberResult] = {}
        self._closing = threading.Event()
        self.start()

    def run(self) -> None:
        while not self._closing.wait(POLL):
            for future in self.futures:
                if future.done():
                    continue
                for task in self.by_key[future.key]:
                    if self._stuck(task):
                        self._stop_member(future, task)
                        break

    def _stuck(self, task: MemberTask) -> bool:
        start = self.starts.get(task.index)
        return start is not None and task.index not in self.stopped and \
            time.monotonic() - start[0] > self.member_timeout + KILL_GRACE

    def _stop_member(self, future: Any, task: MemberTask) -> None:
        start = self.starts.get(task.index)
        assert start is not None
        _, worker, pid = start
        # recorded first: the cancelled future completes as soon as it is cancelled
        self.stopped[task.index] = MemberResult(
            task.index, task.parameters, "failed",
            f"MemberTimeout: still running {self.member_timeout + KILL_GRACE:g} s after it "
            f"started (member_timeout={self.member_timeout:g} s), stuck where the run's "
            f"timeout cannot stop it; its worker process {pid} ({worker}) was restarted",
            "MemberTimeout")
        self.client.cancel([future])
        self.client.restart_workers([worker], raise_for_error=False)

    def close(self) -> None:
        self._closing.set()
        self.join()


def _death(client: Any, pid: int) -> str:
    """", of signal 11 (SIGSEGV, Segmentation fault)" or ", with exit status 3", from the
    nanny's log line about the process; "" when no nanny logged it in time."""
    deadline = time.monotonic() + DEATH_LOG_WAIT
    killed, exited = f"Worker process {pid} was killed by signal ", \
        f"Worker process {pid} exited with status "
    while time.monotonic() < deadline:
        for lines in client.get_worker_logs(nanny=True).values():
            for _, line in lines:
                if killed in line:
                    number = int(line.split(killed, 1)[1].split()[0])
                    return f", of signal {number} ({_signal_name(number)})"
                if exited in line:
                    return f", with exit status {line.split(exited, 1)[1].split()[0]}"
        time.sleep(0.1)
    return ""


def _signal_name(number: int) -> str:
    try:
        return f"{signal.Signals(number).name}, {signal.strsignal(number)}"
    except ValueError:
        return "unknown signal"
