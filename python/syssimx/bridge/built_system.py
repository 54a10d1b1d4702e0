"""An engine system made from a plan's records (ssx_plan_read, ssx_plan_build), given the
FMUs Python loaded. A record the engine refuses is named as the user named it."""

from __future__ import annotations

import re
from typing import Any

from ..engine import ffi, lib
from ..errors import ConfigurationError
from ..plan.records import PlanRecords

_ERROR_SIZE = 2048
# how the builder names the record it refused
_REFUSED_RECORD = re.compile(r"^line (\d+): record '[^']*': (.*)$", re.DOTALL)


def build_system(records: PlanRecords, given: list[Any]) -> Any:
    """The ssx_system of `records` (not yet freed by anyone); given[k]: the loaded FMU of
    component k, or NULL."""
    engine = lib()
    text = records.text().encode()
    error = ffi.new("char[]", _ERROR_SIZE)
    plan = engine.ssx_plan_read(text, len(text), error, _ERROR_SIZE)
    if plan == ffi.NULL:  # the writer's fault, not the user's: the whole reason
        raise ConfigurationError(f"the engine refused the plan: {_text(error)}")
    try:
        fmus = ffi.new("ssx_fmu *[]", given or [ffi.NULL])
        system = engine.ssx_plan_build(plan, b"", fmus, len(given), error, _ERROR_SIZE)
    finally:
        engine.ssx_plan_free(plan)
    if system == ffi.NULL:
        raise ConfigurationError(_named(records, _text(error)))
    return system


def _text(error: Any) -> str:
    return ffi.string(error).decode(errors="replace")


def _named(records: PlanRecords, message: str) -> str:
    """The builder's message with its record named as the user names it."""
    match = _REFUSED_RECORD.match(message)
    about = records.about(int(match[1])) if match else ""
    return f"{about}: {match[2]}" if match and about else message
