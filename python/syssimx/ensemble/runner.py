"""Running members as Dask tasks and turning every outcome into a MemberResult.

Short members share a task, sized from the members' measured time (next_size), so the
scheduler's cost per task is paid once for several; a few tasks per worker are in flight, so a
worker never waits for the client; a task's results come back as one block (block.py). A
member's own failures come back as its result (member.py). Two faults need the client:
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

import signal
import threading
import time
import uuid
from collections import deque
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
# A task costs the client, the scheduler and its worker a few milliseconds of CPU (scheduling,
# messages, the results' transfer) whatever its members: tasks are sized from the members'
# measured time to take about TASK_SECONDS, and MAX_CHUNK members at most (a crash reruns a
# task's members alone).
TASK_SECONDS = 0.03
MAX_CHUNK = 64
# Tasks per worker submitted ahead: a worker starts its next task without waiting for the
# client, and the client assembles results while the workers run.
AHEAD = 2


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


def next_size(remaining: int, workers: int, member_seconds: float | None) -> int:
    """Members for the next task: one until a member's time is known (the first tasks measure
    it), then as many as take about TASK_SECONDS, at most MAX_CHUNK, and never so many that
    the last tasks leave workers idle (each task at most its share of what remains)."""
    if member_seconds is None:
        return 1
    by_time = max(1, round(TASK_SECONDS / max(member_seconds, 1e-9)))
    share = -(-remaining // (AHEAD * max(workers, 1)))
    return max(1, min(by_time, MAX_CHUNK, share))


def announcing(chunk: Sequence[MemberTask], topic: str, every_member: bool) -> list[MemberTask]:
    """The members of a task, those that announce their start on `topic` marked: all when
    `every_member` (the watchdog times each member), else only the first (a worker death is
    pinned on a task of one member only, and each announcement costs the scheduler and the
    client a message)."""
    return [replace(task, topic=topic) if every_member or offset == 0 else task
            for offset, task in enumerate(chunk)]


class _Ensemble:
    """The members' tasks on one client, their starts, and the results so far."""

    def __init__(self, client: Any, build: SystemSource, member_timeout: float | None,
                 bar: ProgressBar) -> None:
        self.client, self.build, self.member_timeout, self.bar = client, build, \
            member_timeout, bar
        self.workers = max(1, len(client.nthreads()))
        self.topic = f"syssimx-ensemble-{uuid.uuid4().hex}"
        self.starts = _Starts()
        self.results: dict[int, MemberResult] = {}
        self.parameters: dict[int, Any] = {}  # by member index
        self._attempt = 0
        self._member_time, self._timed = 0.0, 0

    def run(self, tasks: Sequence[MemberTask], alone: bool = False) -> list[MemberTask]:
        """Run `tasks`, AHEAD tasks per worker in flight, each new one sized from the member
        time measured so far; returns the suspects (see the module's description). `alone`:
        `tasks` is one member run alone on the cluster, so a worker death is its own."""
        from distributed import as_completed

        self._attempt += 1
        waiting = deque(tasks)
        futures: list[Any] = []
        by_key: dict[Any, list[MemberTask]] = {}
        running = as_completed([], with_results=True, raise_errors=False)

        def submit() -> None:
            size = next_size(len(waiting), self.workers, self.member_seconds())
            chunk = announcing([waiting.popleft() for _ in range(min(size, len(waiting)))],
                               self.topic, every_member=self.member_timeout is not None)
            key = f"syssimx-members-{chunk[0].index}-{self.topic[-8:]}-{self._attempt}"
            by_key[key] = chunk  # before the future: the watchdog looks chunks up by key
            future = self.client.submit(run_block, self.build, chunk, key=key, pure=False)
            futures.append(future)
            running.add(future)

        while waiting and len(futures) < AHEAD * self.workers:
            submit()
        watchdog = _Watchdog(self.client, futures, by_key, self.starts, self.member_timeout) \
            if self.member_timeout is not None else None
        suspects: list[MemberTask] = []
        try:
            for future, outcome in running:
                if waiting:  # the next task first: the worker that finished gets it at once
                    submit()
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

    def member_seconds(self) -> float | None:
        """The mean time of the members finished so far, inside their workers."""
        return self._member_time / self._timed if self._timed else None

    def _keep(self, results: Sequence[MemberResult]) -> None:
        for result in results:
            self.results[result.index] = result
            self.bar.advance(not result.ok)
            if result.wall_time == result.wall_time:  # NaN for a member that never ran
                self._member_time += result.wall_time
                self._timed += 1

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
    check_processes(client)
    bar = ProgressBar(len(tasks), progress)
    ensemble = _Ensemble(client, build, member_timeout, bar)
    ensemble.parameters = {task.index: task.parameters for task in tasks}
    client.subscribe_topic(ensemble.topic, ensemble.starts.record)
    try:
        for suspect in ensemble.run(tasks):
            ensemble.run([suspect], alone=True)
    finally:
        bar.close()
        client.unsubscribe_topic(ensemble.topic)
    return [ensemble.results[task.index] for task in tasks]


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
