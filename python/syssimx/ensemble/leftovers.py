"""What members leave behind: processes an FMU forked and did not end. A worker ends them
after each task (SIGKILL, then reaps them), so that they do not outlive the sweep. One scan
of /proc per task: 3-20 ms on the 2-core test machine, so per task, not per member.

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
    me = os.getpid()
    found = set()
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):  # the process ended meanwhile
            continue
        pid, parent, group = int(stat.parent.name), int(fields[1]), int(fields[2])
        if parent == me and group != pid:
            found.add(pid)
    return found


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
