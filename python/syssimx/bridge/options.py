"""Options judged by the engine: Python passes them to a scratch system and maps the answer."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..engine import ffi, lib


def engine_refusal(set_options: Callable[[Any], int]) -> str | None:
    """Why the engine refuses the options `set_options(system)` sets on a new system, or None
    when it accepts them."""
    system = ffi.gc(lib().ssx_system_new(b"options"), lib().ssx_system_free)
    if system == ffi.NULL:
        raise MemoryError("ssx_system_new failed")
    if set_options(system) == 0:
        return None
    return ffi.string(lib().ssx_last_error(system).message).decode(errors="replace")
