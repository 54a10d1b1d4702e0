"""Warnings of outputs that were NaN or infinite though they feed nothing.

The engine stops a run when a non-finite value reaches a connected input or an event indicator;
one in an output that feeds nothing is recorded and the run goes on (as FMPy records it). Each
such output is warned of once per initialize, with the time it first appeared.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from typing import Any, Protocol

from ..engine import ffi, lib
from ..errors import SysSimXWarning


class WatchedPlan(Protocol):
    """What the warning reads of an engine plan (an EnginePlan)."""

    sys: Any
    index: Mapping[str, int]
    outputs: Mapping[str, list[str]]
    non_finite_warned: set[tuple[int, int]]


def warn_non_finite_outputs(plan: WatchedPlan, stacklevel: int = 3) -> None:
    """Warn of each output the engine found non-finite since the last warning (one C call
    when there is none)."""
    count = int(lib().ssx_non_finite_outputs(plan.sys, ffi.NULL, ffi.NULL, ffi.NULL, 0))
    if count <= len(plan.non_finite_warned):
        return
    components, outputs = ffi.new("int[]", count), ffi.new("int[]", count)
    times = ffi.new("double[]", count)
    count = min(count, int(lib().ssx_non_finite_outputs(plan.sys, components, outputs, times,
                                                        count)))
    names = list(plan.index)
    for i in range(count):
        key = (int(components[i]), int(outputs[i]))
        if key in plan.non_finite_warned:
            continue
        plan.non_finite_warned.add(key)
        component = names[key[0]]
        port = plan.outputs[component][key[1]]
        warnings.warn(f"{component}: output {port!r} is NaN or infinite from t={times[i]:.12g}; "
                      "it feeds no input and no event indicator, so it is recorded as it is "
                      "and the run goes on", SysSimXWarning, stacklevel=stacklevel)
