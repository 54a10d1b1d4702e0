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
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    arrived: list[FrameType | None] = []

    def remember(_signal: int, frame: FrameType | None) -> None:
        arrived.append(frame)

    previous: Any = signal.signal(signal.SIGINT, remember)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if arrived and callable(previous):
            previous(signal.SIGINT, arrived[0])
