"""Ctrl-C held back while the embedded cluster starts or closes.

A KeyboardInterrupt raised inside LocalCluster's start or close leaves what was half made
running: nanny and worker processes, the scheduler's sockets, the event loop's thread, and the
workers' extraction folders. Inside `interrupts_deferred()` the first Ctrl-C is noted and
raised when the block ends, so that the cluster is whole and can be closed; a second Ctrl-C
is raised at once (the user insists).
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType


@contextmanager
def interrupts_deferred() -> Iterator[None]:
    """Run the block with Ctrl-C deferred to its end (KeyboardInterrupt raised then). Where
    Python's own SIGINT handler is not the one set (another thread, the program's own
    handler), the block runs as it is."""
    if threading.current_thread() is not threading.main_thread() \
            or signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        yield
        return
    arrived: list[int] = []

    def note(signum: int, _frame: FrameType | None) -> None:
        if arrived:
            raise KeyboardInterrupt
        arrived.append(signum)

    signal.signal(signal.SIGINT, note)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    if arrived:
        raise KeyboardInterrupt
