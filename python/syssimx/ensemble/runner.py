"""Running members as Dask tasks and turning every outcome into a MemberResult.

A member's own failures come back as its result (member.py). Two faults need the client:
- a member still running `member_timeout` (+ KILL_GRACE) seconds after it started is stuck
  where its run's own timeout cannot reach (inside an FMU call): its task is cancelled and its
  worker process restarted (the worker's nanny starts a fresh one);
- a worker process that dies (a segfault in an FMU, an abort, the out-of-memory killer) takes
  down the member it was running and the members queued on it. The member that had announced
  its start there is reported with how the process died (read from its nanny). The others,
  and the one that crashed too fast to announce itself, are suspects: each runs again alone
  on the cluster after the batch, where a worker death can only be its own.
Every other member's result is kept and the ensemble finishes.
"""

from __future__ import annotations

import signal
import threading
import time
import uuid
from collections.abc import Sequence
from dataclasses import replace
from typing import Any

from .member import MemberResult, MemberTask, run_member
from .progress import ProgressBar
from .system_source import SystemSource

KILL_GRACE = 1.0  # seconds past member_timeout: the run's own timeout reports first if it can
POLL = 0.1  # seconds between checks for stuck members
DEATH_LOG_WAIT = 3.0  # seconds to wait for a nanny to log how its worker died


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


class _Ensemble:
    """The members' tasks on one client, their starts, and the results so far."""

    def __init__(self, client: Any, build: SystemSource, member_timeout: float | None,
                 bar: ProgressBar) -> None:
        self.client, self.build, self.member_timeout, self.bar = client, build, \
            member_timeout, bar
        self.topic = f"syssimx-ensemble-{uuid.uuid4().hex}"
        self.starts = _Starts()
        self.results: dict[int, MemberResult] = {}
        self._attempt = 0

    def run(self, tasks: Sequence[MemberTask], alone: bool) -> list[MemberTask]:
        """Run `tasks` as one batch; returns the suspects (see the module's description).
        `alone`: the batch is one member, so a worker death is that member's."""
        from distributed import as_completed

        self._attempt += 1
        # a task per member, so a crash takes no finished member with it
        futures = self.client.map(
            run_member, [self.build] * len(tasks),
            [replace(task, topic=self.topic) for task in tasks],
            key=[f"syssimx-member-{t.index}-{self.topic[-8:]}-{self._attempt}" for t in tasks],
            pure=False)
        by_key = {future.key: task for future, task in zip(futures, tasks, strict=True)}
        watchdog = _Watchdog(self.client, futures, by_key, self.starts, self.member_timeout) \
            if self.member_timeout is not None else None
        suspects = []
        try:
            for future, outcome in as_completed(futures, with_results=True, raise_errors=False):
                task = by_key[future.key]
                stopped = watchdog.stopped.get(task.index) if watchdog is not None else None
                result = stopped or self._outcome(future, outcome, task, alone)
                if result is None:
                    suspects.append(task)
                    continue
                self.results[task.index] = result
                self.bar.advance(not result.ok)
        finally:
            if watchdog is not None:
                watchdog.close()
            self.client.cancel([future for future in futures if not future.done()])
        return suspects

    def _outcome(self, future: Any, outcome: Any, task: MemberTask, alone: bool
                 ) -> MemberResult | None:
        """The member's result; None for a suspect."""
        if future.status == "finished":
            return outcome
        from distributed.scheduler import KilledWorker

        error = future.exception()
        if not isinstance(error, KilledWorker):
            # the task failed before the member's code ran (e.g. its function did not unpickle)
            return MemberResult(task.index, task.parameters, "failed",
                                f"{type(error).__name__}: {error}", type(error).__name__)
        dead = error.last_worker
        start = self.starts.get(task.index)
        if not alone and (start is None or start[2] != dead.pid):
            return None
        reason = (f"WorkerDied: the worker process {dead.pid} ({dead.address}) died while "
                  f"running this member{_death(self.client, dead.pid)}")
        return MemberResult(task.index, task.parameters, "failed", reason, "WorkerDied")


def run_members(client: Any, build: SystemSource, tasks: Sequence[MemberTask],
                member_timeout: float | None, progress: bool) -> list[MemberResult]:
    """Every member's result, in member order."""
    bar = ProgressBar(len(tasks), progress)
    ensemble = _Ensemble(client, build, member_timeout, bar)
    client.subscribe_topic(ensemble.topic, ensemble.starts.record)
    try:
        for suspect in ensemble.run(tasks, alone=False):
            ensemble.run([suspect], alone=True)
    finally:
        bar.close()
        client.unsubscribe_topic(ensemble.topic)
    return [ensemble.results[task.index] for task in tasks]


class _Watchdog(threading.Thread):
    """Stops members running past member_timeout + KILL_GRACE: cancels the task (so it is not
    run again) and restarts its worker process."""

    def __init__(self, client: Any, futures: Sequence[Any], by_key: dict[Any, MemberTask],
                 starts: _Starts, member_timeout: float) -> None:
        super().__init__(name="syssimx-ensemble-watchdog", daemon=True)
        self.client, self.futures, self.by_key = client, futures, by_key
        self.starts, self.member_timeout = starts, member_timeout
        self.stopped: dict[int, MemberResult] = {}
        self._closing = threading.Event()
        self.start()

    def run(self) -> None:
        while not self._closing.wait(POLL):
            now = time.monotonic()
            for future in self.futures:
                task = self.by_key[future.key]
                start = self.starts.get(task.index)
                if start is None or future.done() or task.index in self.stopped or \
                        now - start[0] <= self.member_timeout + KILL_GRACE:
                    continue
                self._stop_member(future, task, start[1], start[2])

    def _stop_member(self, future: Any, task: MemberTask, worker: str, pid: int) -> None:
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
