"""SIGTERM during a run stops it as Ctrl-C does: the step in progress ends, a streamed file gets
every sample recorded, and the run raises RunTerminated (a SystemExit, status 143) with the
partial result. Killed by the signal's default action instead, the process would leave its
stream without the samples still in memory."""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from types import FrameType
from typing import Any

# syssimx's own SIGTERM handler (it removes extraction folders, then ends the process) is
# replaced during a run like the default action; a handler of the program's is left alone
_OWN_HANDLER_MODULE = "syssimx.fmu.extraction"


@dataclass
class Termination:
    requested: bool = False


def _ours_to_replace(handler: Any) -> bool:
    return handler == signal.SIG_DFL or getattr(handler, "__module__", None) == \
        _OWN_HANDLER_MODULE


@contextmanager
def sigterm_stops_the_run() -> Iterator[Termination]:
    """Inside, SIGTERM is delivered as SIGINT would be (to Python's handler, which raises
    KeyboardInterrupt where the run looks at signals, or held back while a block of samples is
    written), and the returned Termination says that it came. Python runs signal handlers in the
    main thread only: elsewhere nothing is changed."""
    termination = Termination()
    previous = signal.getsignal(signal.SIGTERM)
    if threading.current_thread() is not threading.main_thread() or \
            not _ours_to_replace(previous):
        yield termination
        return

    def stop(_signal: int, frame: FrameType | None) -> None:
        termination.requested = True
        interrupt = signal.getsignal(signal.SIGINT)
        if callable(interrupt):
            interrupt(signal.SIGINT, frame)
        else:  # Ctrl-C ignored or left to the default action: SIGTERM still stops the run
            raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, stop)
    try:
        yield termination
    finally:
        signal.signal(signal.SIGTERM, previous)
