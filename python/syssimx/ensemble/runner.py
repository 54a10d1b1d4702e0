"""Running members as Dask tasks and turning every outcome into a MemberResult.

Short members share a task, so the scheduler's cost per task is paid once for several, and a
task's results come back as one block (block.py). A large ensemble first runs a probe: one
chunk of PROBE members per worker; the CPU time of the first probe block's members after its
first (which built the System and loaded what it needs: 2.5 s of pint for the seed scenario,
against 1-2 ms for a member after it) is the member's cost, and the rest goes in chunks of
about TASK_SECONDS of CPU each (chunk_size's bounds kept). The cost is remembered for the
system and run (t0, tf, dt, outputs): a later ensemble of them in this process is cut by it
at once, without a probe. A member's own failures come back as its result (member.py). Two
faults need the client:
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
from collections.abc import Callable, Sequence
from typing import Any

from .block import MemberBlock
from .chunk import Experiment, MemberChunk, run_chunk
from .cluster import check_processes
from .member import MemberResult
from .member_list import MemberList
from .members import ParameterSet, ParameterTable
from .progress import ProgressBar
from .system_source import SystemSource

KILL_GRACE = 1.0  # seconds past member_timeout: the run's own timeout reports first if it can
POLL = 0.1  # seconds between checks for stuck members
DEATH_LOG_WAIT = 10.0  # seconds at most to wait for a nanny to log how its worker died
# members per task at most: a task costs the client's process 2.5-4 ms of CPU on the 2-core
# VM whatever its size (scheduling, messages, fetching the result from the worker); a crash
# reruns its chunk's members alone, one task each
MAX_CHUNK = 1024
# tasks per worker at least, for the balance: a worker slowed by others' load ends about a
# task after the rest. Each task
# costs the client a seed member's CPU 3-4 times over: 4 tasks per worker were 0.02 ms of
# its 0.05 ms per member for 2000 seed members on 2 workers.
CHUNKS_PER_WORKER = 3
PROBE = 4  # members per probe chunk
PROBED_FROM = 16  # members per worker from which an ensemble starts with a probe
# a task's target CPU time: its cost to the client stays under 1 % of it, while progress,
# Ctrl-C (the finished tasks are kept) and a crash's reruns stay at half a second (on an
# unloaded machine)
TASK_SECONDS = 0.5
# how many systems and runs a member's cost is remembered for (the last ones run): a probe
# is W tasks more, 2 of a sweep's 8 for 2000 seed members on two workers
REMEMBERED = 32
_COSTS: dict[tuple[Any, ...], float] = {}


def remembered_cost(build: SystemSource, experiment: Experiment) -> float | None:
    """The member cost last measured for this system and run, if any."""
    key = _cost_key(build, experiment)
    return None if key is None else _COSTS.get(key)


def remember_cost(build: SystemSource, experiment: Experiment, cost: float) -> None:
    key = _cost_key(build, experiment)
    if key is None:
        return
    _COSTS.pop(key, None)
    _COSTS[key] = cost  # the newest last: the oldest goes first
    while len(_COSTS) > REMEMBERED:
        del _COSTS[next(iter(_COSTS))]


def _cost_key(build: SystemSource, experiment: Experiment) -> tuple[Any, ...] | None:
    """What a member's cost depends on besides its parameters; None for a system function
    that cannot be a key (an object without a hash)."""
    key = (build, experiment.t0, experiment.tf, experiment.dt, experiment.outputs)
    try:
        hash(key)
    except TypeError:
        return None
    return key


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
    scheduler is paid once for several; CHUNKS_PER_WORKER tasks per worker keep the load
    balanced (rounded up: 2000 members on 2 workers are 6 chunks of 333-334; chunks of at
    most 333 were 7, made 8 of 250 for an even count)."""
    return max(1, min(MAX_CHUNK, -(-members // (CHUNKS_PER_WORKER * max(workers, 1)))))


def sized(members: int, workers: int, cost: float | None) -> int:
    """Members per task for `members` members of `cost` seconds each (None: not measured):
    chunk_size's, or fewer where a task would take longer than TASK_SECONDS."""
    size = chunk_size(members, workers)
    return size if cost is None or cost <= 0 else max(1, min(size, round(TASK_SECONDS / cost)))


def split(sets: Sequence[ParameterSet], size: int, workers: int, experiment: Experiment,
          topic: str | None = None, announce_each: bool = False, first: int = 0
          ) -> list[MemberChunk]:
    """The members of `sets` (indices first, first + 1, ...) in chunks of `size` at most, as
    many chunks as a multiple of `workers` and of sizes differing by one at most, so no worker
    is left with a last chunk alone."""
    count = -(-len(sets) // size)
    count = min(len(sets), -(-count // workers) * workers)
    bounds = [len(sets) * k // count for k in range(count + 1)]
    return [MemberChunk(first + start, sets[start:stop], experiment, topic, announce_each)
            for start, stop in itertools.pairwise(bounds)]


class _Ensemble:
    """The members' tasks on one client, their starts, and the results so far."""

    def __init__(self, client: Any, build: SystemSource, experiment: Experiment,
                 sets: ParameterTable, bar: ProgressBar, workers: int) -> None:
        self.client, self.build, self.experiment, self.sets, self.bar = client, build, \
            experiment, sets, bar
        self.member_timeout = experiment.timeout
        self.workers = max(1, workers)
        # one function object for every task: Dask serializes it once, not per task
        self.task = functools.partial(run_chunk, build)
        self.topic = f"syssimx-ensemble-{uuid.uuid4().hex}"
        self.starts = _Starts()
        self._subscribed = False  # to the topic: from the first chunk whose members announce
        self.results = MemberList(sets)
        self._attempt = 0

    def run(self, chunks: Sequence[MemberChunk], alone: bool,
            later: Callable[[MemberBlock | None], list[MemberChunk]] | None = None) -> list[int]:
        """Run `chunks`, and the chunks `later` gives for the first outcome (its block, None
        for a failed task); returns the suspects' member indices (see the module's
        description). A chunk of one member `alone` on the cluster makes a worker death that
        member's."""
        from distributed import as_completed

        self._attempt += 1
        futures: list[Any] = []
        by_key: dict[Any, MemberChunk] = {}  # both grow as `later`'s chunks are submitted
        pending = as_completed(with_results=True, raise_errors=False)
        self._submit(chunks, futures, by_key, pending)
        watchdog = _Watchdog(self.client, futures, by_key, self.starts, self.sets,
                             self.member_timeout) if self.member_timeout is not None else None
        suspects: list[int] = []
        try:
            for future, outcome in pending:
                chunk = by_key[future.key]
                if later is not None:
                    self._submit(later(outcome if future.status == "finished" else None),
                                 futures, by_key, pending)
                    later = None
                if future.status == "finished":
                    self.bar.advance(*self.results.add_block(outcome))
                    if outcome.cost is not None:
                        remember_cost(self.build, self.experiment, outcome.cost)
                elif future.status == "cancelled":  # the watchdog stopped one of its members
                    assert watchdog is not None
                    self._keep([watchdog.stopped[i] for i in chunk.indices
                                if i in watchdog.stopped])
                    suspects += [i for i in chunk.indices if i not in watchdog.stopped]
                else:
                    suspects += self._failed(future.exception(), chunk, alone)
        except KeyboardInterrupt:
            self._keep_finished(pending)
            raise
        finally:
            if watchdog is not None:
                watchdog.close()
            running = [future for future in futures if not future.done()]
            if running:  # a round trip to the scheduler, even for none
                self.client.cancel(running)
        return suspects

    def _keep_finished(self, pending: Any) -> None:
        """On Ctrl-C: the members whose task had finished, with its result here, but that
        `run` had not taken yet."""
        for future, outcome in pending.next_batch(block=False):
            if future.status == "finished":
                self.bar.advance(*self.results.add_block(outcome))

    def _submit(self, chunks: Sequence[MemberChunk], futures: list[Any],
                by_key: dict[Any, MemberChunk], pending: Any) -> None:
        if not self._subscribed and any(chunk.announced for chunk in chunks):
            # sent before the tasks on the same stream: the scheduler has it before they run
            self.client.subscribe_topic(self.topic, self.starts.record)
            self._subscribed = True
        submitted = self.client.map(
            self.task, chunks,
            key=[f"syssimx-members-{c.first}-{self.topic[-8:]}-{self._attempt}"
                 for c in chunks], pure=False)
        by_key.update((future.key, chunk)
                      for future, chunk in zip(submitted, chunks, strict=True))
        futures += submitted
        pending.update(submitted)

    def close(self) -> None:
        if self._subscribed:
            self.client.unsubscribe_topic(self.topic)

    def after_probe(self, probed: int, block: MemberBlock | None) -> list[MemberChunk]:
        """The chunks of the members after the first `probed`, sized by `block`'s members."""
        rest = self.sets[probed:]
        size = sized(len(rest), self.workers, block.cost if block else None)
        return split(rest, size, self.workers, self.experiment, self.topic,
                     self.member_timeout is not None, first=probed)

    def _keep(self, results: Sequence[MemberResult]) -> None:
        for result in results:
            self.results.add(result)
        self.bar.advance(len(results), sum(not result.ok for result in results))

    def _failed(self, error: BaseException, chunk: MemberChunk, alone: bool) -> list[int]:
        """Results for a chunk whose task failed; returns its suspects."""
        from distributed.scheduler import KilledWorker

        if not isinstance(error, KilledWorker):
            # the task failed before the members' code ran (e.g. the function did not unpickle)
            self._keep([MemberResult(i, self.sets[i], "failed",
                                     f"{type(error).__name__}: {error}", type(error).__name__)
                        for i in chunk.indices])
            return []
        dead = error.last_worker
        start = self.starts.get(chunk.first)
        # one member that announced its start on the dead process: nobody else was running
        if alone or (len(chunk) == 1 and start is not None and start[2] == dead.pid):
            # the process the member announced its start from: the scheduler's record of the
            # dead worker can name the process that ran there before a restart
            pid = start[2] if start is not None else dead.pid
            reason = (f"WorkerDied: the worker process {pid} ({dead.address}) died while "
                      f"running this member{_death(self.client, pid)}")
            self._keep([MemberResult(chunk.first, self.sets[chunk.first], "failed", reason,
                                     "WorkerDied")])
            return []
        return list(chunk.indices)


def run_members(client: Any, build: SystemSource, experiment: Experiment,
                sets: ParameterTable, progress: bool) -> MemberList:
    """Every member's result (member k runs `sets[k]`), in member order."""
    from .worker_signals import register

    workers = check_processes(client)
    register(client)
    bar = ProgressBar(len(sets), progress)
    ensemble = _Ensemble(client, build, experiment, sets, bar, workers)
    announce_each = experiment.timeout is not None
    cost = remembered_cost(build, experiment)
    try:
        if cost is None and len(sets) >= PROBED_FROM * workers:
            probed = PROBE * workers
            suspects = ensemble.run(
                split(sets[:probed], PROBE, workers, experiment, ensemble.topic, announce_each),
                alone=False, later=functools.partial(ensemble.after_probe, probed))
        else:
            suspects = ensemble.run(split(sets, sized(len(sets), workers, cost), workers,
                                          experiment, ensemble.topic, announce_each),
                                    alone=False)
        for suspect in suspects:
            ensemble.run([MemberChunk(suspect, sets[suspect:suspect + 1], experiment,
                                      ensemble.topic, announce_each)], alone=True)
    except KeyboardInterrupt as stop:  # Ctrl-C: the finished members are kept
        raise _interrupted(ensemble, sets) from stop
    finally:
        try:
            try:
                bar.close()
            finally:
                ensemble.close()
        except KeyboardInterrupt as stop:  # Ctrl-C while closing, after every member too
            raise _interrupted(ensemble, sets) from stop
    return ensemble.results


def _interrupted(ensemble: _Ensemble, sets: ParameterTable) -> MembersInterrupted:
    """The interrupt carrying every member's result, the unfinished ones failed."""
    for index, values in enumerate(sets):
        if not ensemble.results.has(index):
            ensemble.results.add(MemberResult(
                index, values, "failed", "interrupted (Ctrl-C) before it finished",
                "KeyboardInterrupt"))
    return MembersInterrupted(ensemble.results)


class MembersInterrupted(KeyboardInterrupt):
    """Ctrl-C during run_members: every member's result, the unfinished ones failed."""

    def __init__(self, results: MemberList) -> None:
        super().__init__("interrupted")
        self.results = results


class _Watchdog(threading.Thread):
    """Stops members running past member_timeout + KILL_GRACE: cancels their task (so it is
    not run again) and restarts its worker process."""

    def __init__(self, client: Any, futures: Sequence[Any], by_key: dict[Any, MemberChunk],
                 starts: _Starts, sets: Sequence[ParameterSet], member_timeout: float) -> None:
        super().__init__(name="syssimx-ensemble-watchdog", daemon=True)
        self.client, self.futures, self.by_key = client, futures, by_key
        self.starts, self.sets, self.member_timeout = starts, sets, member_timeout
        self.stopped: dict[int, MemberResult] = {}
        self._closing = threading.Event()
        self.start()

    def run(self) -> None:
        while not self._closing.wait(POLL):
            for future in self.futures:
                if future.done():
                    continue
                for index in self.by_key[future.key].indices:
                    if self._stuck(index):
                        self._stop_member(future, index)
                        break

    def _stuck(self, index: int) -> bool:
        start = self.starts.get(index)
        return start is not None and index not in self.stopped and \
            time.monotonic() - start[0] > self.member_timeout + KILL_GRACE

    def _stop_member(self, future: Any, index: int) -> None:
        start = self.starts.get(index)
        assert start is not None
        _, worker, pid = start
        # recorded first: the cancelled future completes as soon as it is cancelled
        self.stopped[index] = MemberResult(
            index, self.sets[index], "failed",
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
