"""Turning an engine failure (ssx_error plus a kept Python exception) into a SimulationError."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, NoReturn, Protocol

from ..engine import ffi, lib, status_name
from ..errors import (
    AlgebraicLoopError,
    ConfigurationError,
    SimulationError,
    SimulationTimeoutError,
    ZenoError,
)


class FailedPlan(Protocol):
    """What a failure reads of the engine plan it happened in (an EnginePlan)."""

    sys: Any
    failure: Any
    index: Mapping[str, int]
    indicators: list[tuple[str, str]]
    components: Mapping[str, Any]
    outputs: Mapping[str, list[str]]

# The exception of each kind of engine failure (ssx_error_kind) that has one of its own.
_EXCEPTIONS: dict[str, type[SimulationError]] = {"SSX_ERROR_ZENO": ZenoError,
                                                 "SSX_ERROR_LOOP": AlgebraicLoopError}


def raise_failure(plan: FailedPlan, default_component: str | None = None) -> NoReturn:
    """Raise the plan's last failure. An interrupt (KeyboardInterrupt, SystemExit) raised in a
    callback and a timeout are raised as they are, arguments the engine refused (a step that is
    not positive, ...) as ConfigurationError; anything else becomes a SimulationError."""
    error = lib().ssx_last_error(plan.sys)
    if error.kind == lib().SSX_ERROR_CONFIG:
        raise ConfigurationError(ffi.string(error.message).decode(errors="replace"))
    failure = plan.failure
    if failure is not None and (not isinstance(failure.error, Exception)
                                or isinstance(failure.error, SimulationTimeoutError)):
        plan.failure = None
        raise failure.error
    raise simulation_error(plan, default_component)


def simulation_error(plan: FailedPlan, default_component: str | None = None) -> SimulationError:
    """The exception for the plan's last failure; clears the kept callback failure."""
    error = lib().ssx_last_error(plan.sys)
    message = ffi.string(error.message).decode(errors="replace")
    names = list(plan.index)
    component = names[error.component] if 0 <= error.component < len(names) \
        else default_component
    event = plan.indicators[error.indicator][1] if 0 <= error.indicator < len(
        plan.indicators) else None
    time = None if math.isnan(error.time) else float(error.time)
    failure, plan.failure = plan.failure, None
    if error.kind == lib().SSX_ERROR_CALLBACK and failure is not None:
        text = (f"{failure.component}: {failure.where} raised "
                f"{type(failure.error).__name__}: {failure.error} at t={failure.time:.12g}")
        exc = SimulationError(text, component=failure.component, time=failure.time,
                              event=event)
        exc.__cause__ = failure.error
        return exc
    status = int(error.fmi_status) if error.fmi_status >= 0 else None
    kind = _EXCEPTIONS.get(ffi.string(ffi.cast("ssx_error_kind", error.kind)),
                           SimulationError)
    fmu_message = ""
    if component is not None and component in plan.components:
        instance = getattr(plan.components[component], "instance", None)
        if instance is not None:
            fmu_message = ffi.string(lib().ssx_fmu_last_message(instance.fmu)).decode(
                errors="replace")
    text = message
    if error.output >= 0 and component in plan.outputs:
        # the engine numbers outputs; the user knows them by name
        port = plan.outputs[component][error.output]
        text = text.replace(f"output {error.output} is", f"output {port!r} is", 1)
    if status is not None and status_name(status) not in text:
        text += f" (status {status_name(status)})"
    return kind(text, component=component, time=time, status=status, fmu_message=fmu_message,
                event=event)
