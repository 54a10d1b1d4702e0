"""Ctrl-C held back while a block of samples is written: a file then ends on a whole block, and
it holds every sample the history holds. The interrupt is raised as the block is done."""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType
from typing import Any


@contextmanager
def interrupts_deferred() -> Iterator[None]:
    """SIGINT that arrives inside is remembered and handed to the handler that was in place when
    the block ends. Python runs signal handlers in the main thread only: elsewhere nothing is
    needed, and nothing is done."""
    previous: Any = signal.getsignal(signal.SIGINT)
    # elsewhere than the main thread, or under a handler not set from Python (which could not
    # be put back): nothing held back
    if threading.current_thread() is not threading.main_thread() or previous is None:
        yield
        return
    arrived: list[FrameType | None] = []

    def remember(_signal: int, frame: FrameType | None) -> None:
        arrived.append(frame)

    signal.signal(signal.SIGINT, remember)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if arrived:
            deliver(previous, arrived[0])


def deliver(handler: Any, frame: FrameType | None) -> None:
    """What SIGINT would have done under `handler` (Python's, the default's, or ignored)."""
    if callable(handler):
        handler(signal.SIGINT, frame)
    elif handler == signal.SIG_DFL:
        signal.raise_signal(signal.SIGINT)
