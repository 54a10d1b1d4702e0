"""What members leave behind: processes an FMU forked and did not end. A worker ends them
after each task (SIGKILL, then reaps them), so that they do not outlive the sweep. Per task,
not per member: the children are read from the kernel's list of each of the worker's threads
(/proc/self/task/*/children, about 0.1 ms); where the kernel has no such list, from a scan of
every process's /proc entry (8 ms on the 2-core test machine with 80 processes, 3-20 ms as
their number varies; twice per task, it was 0.1 ms of a seed member's 0.94 ms).

A child counts when it appeared during the member and does not lead a process group of its
own: an isolated FMU's host leads its own (and a reused System keeps its hosts between
members); a process an FMU forks shares the worker's group.
"""

from __future__ import annotations

import os
import signal
from pathlib import Path


def children() -> set[int]:
    """This process's children that do not lead their own process group, read from /proc."""
    listed = _listed_children()
    me = os.getpid()
    stats = [Path(f"/proc/{pid}/stat") for pid in listed] if listed is not None \
        else Path("/proc").glob("[0-9]*/stat")
    found = set()
    for stat in stats:
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):  # the process ended meanwhile
            continue
        pid, parent, group = int(stat.parent.name), int(fields[1]), int(fields[2])
        if parent == me and group != pid:
            found.add(pid)
    return found


def _listed_children() -> set[int] | None:
    """The children the kernel lists for this process's threads (a child is listed under the
    thread that forked it); None where it keeps no such list."""
    listed: set[int] = set()
    for thread in Path("/proc/self/task").iterdir():
        try:
            listed.update(int(pid) for pid in (thread / "children").read_text().split())
        except FileNotFoundError:
            if not thread.exists():  # the thread ended meanwhile
                continue
            return None
    return listed


_AT_START: set[int] | None = None  # the worker's own children, seen at its first task


def end_left_children() -> list[int]:
    """End (SIGKILL) and reap the children that appeared since the first call in this process
    (those it had then are the worker's own); returns them. Only in a worker process of its
    own (a nanny's child): a worker thread inside the user's process leaves its children be."""
    global _AT_START
    import multiprocessing

    if multiprocessing.parent_process() is None:
        return []
    if _AT_START is None:
        _AT_START = children()
        return []
    return end_new_children(_AT_START)


def end_new_children(before: set[int]) -> list[int]:
    """End (SIGKILL) and reap the children that were not there `before`; returns them."""
    ended = sorted(children() - before)
    for pid in ended:
        try:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
        except (ProcessLookupError, ChildProcessError):
            pass
    return ended
