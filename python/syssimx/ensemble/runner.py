"""Running members as Dask tasks and turning every outcome into a MemberResult.

A member's own failures come back as its result (member.py). Two faults need the client:
- a member still running `member_timeout` (+ KILL_GRACE) seconds after it started is stuck
  where its run's own timeout cannot reach (inside an FMU call): its task is cancelled and its
  worker process restarted (the worker's nanny starts a fresh one);
- a worker process that dies while running a member (a segfault in an FMU, an abort, the
  out-of-memory killer) fails that member with how the process died, read from its nanny.
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


def run_members(client: Any, build: SystemSource, tasks: Sequence[MemberTask],
                member_timeout: float | None, progress: bool) -> list[MemberResult]:
    """Every member's result, in member order."""
    from distributed import wait

    topic = f"syssimx-ensemble-{uuid.uuid4().hex}"
    starts = _Starts()
    client.subscribe_topic(topic, starts.record)
    futures = {client.submit(run_member, build, replace(task, topic=topic),
                             key=f"syssimx-member-{task.index}-{topic[-8:]}", pure=False): task
               for task in tasks}
    results: dict[int, MemberResult] = {}
    bar = ProgressBar(len(tasks), progress)
    pending = set(futures)
    try:
        while pending:
            try:
                done, pending = wait(pending, timeout=POLL if member_timeout else None,
                                     return_when="FIRST_COMPLETED")
            except TimeoutError:
                done = set()
            for future in done:
                task = futures[future]
                results[task.index] = _outcome(client, future, task, starts)
                bar.advance(not results[task.index].ok)
            for future in _stuck(pending, futures, starts, member_timeout):
                pending.discard(future)
                task = futures[future]
                results[task.index] = _stop_stuck(client, future, task, starts, member_timeout)
                bar.advance(True)
    finally:
        bar.close()
        client.unsubscribe_topic(topic)
        client.cancel(list(pending))
    return [results[task.index] for task in tasks]


def _outcome(client: Any, future: Any, task: MemberTask, starts: _Starts) -> MemberResult:
    if future.status == "finished":
        return future.result()
    from distributed.scheduler import KilledWorker

    error = future.exception()
    if isinstance(error, KilledWorker):
        start = starts.get(task.index)
        pid = start[2] if start is not None else error.last_worker.pid
        reason = (f"WorkerDied: the worker process {pid} ({error.last_worker.address}) died "
                  f"while running this member{_death(client, pid)}")
        return MemberResult(task.index, task.parameters, "failed", reason, "WorkerDied")
    # the task failed before the member's code ran (e.g. the system function did not unpickle)
    return MemberResult(task.index, task.parameters, "failed",
                        f"{type(error).__name__}: {error}", type(error).__name__)


def _stuck(pending: set[Any], futures: dict[Any, MemberTask], starts: _Starts,
           member_timeout: float | None) -> list[Any]:
    if member_timeout is None:
        return []
    now = time.monotonic()
    stuck = []
    for future in pending:
        start = starts.get(futures[future].index)
        if start is not None and now - start[0] > member_timeout + KILL_GRACE:
            stuck.append(future)
    return stuck


def _stop_stuck(client: Any, future: Any, task: MemberTask, starts: _Starts,
                member_timeout: float) -> MemberResult:
    start = starts.get(task.index)
    assert start is not None  # only started members are stuck
    _, worker, pid = start
    client.cancel([future])
    client.restart_workers([worker], raise_for_error=False)
    return MemberResult(task.index, task.parameters, "failed",
                        f"MemberTimeout: still running {member_timeout + KILL_GRACE:g} s after "
                        f"it started (member_timeout={member_timeout:g} s), stuck where the "
                        f"run's timeout cannot stop it; its worker process {pid} ({worker}) "
                        "was restarted", "MemberTimeout")


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
