"""Writing a command's results: Ctrl-C during the write lets it finish (the run is done, its
file is what is left of it), and a write that takes a while shows a bar on a terminal."""

from __future__ import annotations

import signal
import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType
from typing import Any

# a write that takes longer than this (seconds) shows its bar
BAR_DELAY = 1.0


@contextmanager
def finished_despite_ctrl_c(what: str) -> Iterator[None]:
    """The block (writing `what`) runs to its end through a first Ctrl-C, which is raised as
    KeyboardInterrupt after it; a second Ctrl-C abandons the write (an atomic write then leaves
    the previous file). Python handles signals in the main thread only: elsewhere nothing is
    held back."""
    previous: Any = signal.getsignal(signal.SIGINT)
    if threading.current_thread() is not threading.main_thread() or previous is None:
        yield
        return
    pressed: list[bool] = []

    def on_ctrl_c(_signal: int, _frame: FrameType | None) -> None:
        if pressed:
            raise KeyboardInterrupt(f"the write of {what} was abandoned")
        pressed.append(True)
        print(f"syssimx: finishing the write of {what} first (Ctrl-C again abandons it)",
              file=sys.stderr, flush=True)

    signal.signal(signal.SIGINT, on_ctrl_c)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
    if pressed:
        raise KeyboardInterrupt(f"after {what} was written")


def write_bar(what: str, rows: int, shown: bool) -> Any:
    """A tqdm bar over `rows` rows that appears once the write has taken BAR_DELAY seconds,
    when `shown` (a terminal, no --quiet); None otherwise."""
    if not shown:
        return None
    from tqdm import tqdm

    return tqdm(total=rows, unit="row", unit_scale=True, desc=f"writing {what}",
                file=sys.stderr, delay=BAR_DELAY, leave=False, mininterval=0.5)
