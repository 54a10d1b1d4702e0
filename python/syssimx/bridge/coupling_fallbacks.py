"""Warnings of what the coupling did instead of what was asked: FMUs that refused an input
derivative order or told non-finite output derivatives (the engine's ssx_coupling_fallbacks),
steps at the step control's min_step still over its tolerance, and coupled inputs its error
cannot measure. Each is warned of once per initialize; the statistics count them."""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from typing import Any, Protocol

from ..engine import ffi, lib
from ..errors import SysSimXWarning


class CoupledPlan(Protocol):
    """What the warnings read of an engine plan (an EnginePlan)."""

    sys: Any
    index: Mapping[str, int]
    coupling_warned: set[tuple[int, str]]


def warn_coupling_fallbacks(plan: CoupledPlan, stacklevel: int = 3) -> None:
    """Warn of each fallback and of steps over the tolerance at min_step not warned of yet."""
    count = int(lib().ssx_coupling_fallbacks(plan.sys, ffi.NULL, 0))
    if count > 0:
        fallbacks = ffi.new("ssx_coupling_fallback[]", count)
        count = min(count, int(lib().ssx_coupling_fallbacks(plan.sys, fallbacks, count)))
        names = list(plan.index)
        for fallback in fallbacks[0:count]:
            _warn_fallback(plan, names[fallback.component], fallback, stacklevel + 1)
    statistics = ffi.new("ssx_statistics *")
    lib().ssx_get_statistics(plan.sys, statistics)
    if statistics.steps_over_tolerance > 0 and (-1, "tolerance") not in plan.coupling_warned:
        plan.coupling_warned.add((-1, "tolerance"))
        warnings.warn(f"{statistics.steps_over_tolerance} communication step(s) at the step "
                      "control's min_step still exceeded its tolerance (largest error "
                      f"{statistics.largest_error:.3g} times it): the result is less accurate "
                      "than rtol and atol ask. Lower min_step, or StepControl(strict=True) to "
                      "stop there instead", SysSimXWarning, stacklevel=stacklevel)
    if statistics.unmeasured_inputs > 0 and (-1, "unmeasured") not in plan.coupling_warned:
        plan.coupling_warned.add((-1, "unmeasured"))
        warnings.warn(f"{statistics.unmeasured_inputs} coupled input(s) carry String or Binary "
                      "values, which the step control's coupling error cannot measure: their "
                      "coupling is left out of the error (statistics.unmeasured_inputs)",
                      SysSimXWarning, stacklevel=stacklevel)


def _warn_fallback(plan: CoupledPlan, name: str, fallback: Any, stacklevel: int) -> None:
    component = int(fallback.component)
    if not math.isnan(fallback.input_order_time) and \
            (component, "input order") not in plan.coupling_warned:
        plan.coupling_warned.add((component, "input order"))
        order = int(fallback.input_order)
        instead = f"order {order}" if order > 0 else \
            "order 0: its inputs are held over each step"
        warnings.warn(f"{name}: the FMU refused the input derivative order it was given "
                      "(its SetRealInputDerivatives returned Discard or Error at "
                      f"t={fallback.input_order_time:.12g}); it is given {instead} from then on",
                      SysSimXWarning, stacklevel=stacklevel)
    if not math.isnan(fallback.output_derivatives_time) and \
            (component, "output derivatives") not in plan.coupling_warned:
        plan.coupling_warned.add((component, "output derivatives"))
        warnings.warn(f"{name}: the FMU's output derivatives are NaN or infinite at "
                      f"t={fallback.output_derivatives_time:.12g}; from then on its outputs' "
                      "slopes are estimated from its communication points instead",
                      SysSimXWarning, stacklevel=stacklevel)
