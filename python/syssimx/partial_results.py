"""What the command line keeps of a run stopped by Ctrl-C: the finished part, written where the
whole would have gone, then the interrupt raised again (exit status 130)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

from .errors import RunInterrupted

Result = TypeVar("Result")


def run_keeping_partial(run: Callable[[], Result]) -> tuple[Result, RunInterrupted | None]:
    """run()'s result and None; after Ctrl-C, the partial result and the interrupt to raise
    once it is written."""
    try:
        return run(), None
    except RunInterrupted as stop:
        partial: Any = stop.partial_result
        return partial, stop
