"""The whole system's state by handle (System.save_state), put back (System.restore_state) or
turned into bytes and back (SystemState.to_bytes, System.state_from_bytes).

A state belongs to the engine system and the FMU instances it was saved from: it keeps that
system alive, and is freed before it (by close() or when it is collected).
"""

from __future__ import annotations

import weakref
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from ..engine import ffi, lib
from ..errors import StateError
from ..fmu.instance import FMUInstance
from .termination import Termination, read_termination

if TYPE_CHECKING:
    from ..bridge.plan import EnginePlan


class SystemState:
    """The state of every component and of the engine (port values, indicators, the event
    and step control state, the grid, the statistics) at one instant of one System. Free it
    early with close(); it is freed anyway when no longer referenced."""

    def __init__(self, plan: EnginePlan, handle: Any) -> None:
        self._plan = plan
        self._handle = handle
        # the finalizer holds the engine system, so that the system and its FMUs outlive the
        # state; it skips the engine's free once a component's FMU was freed (component.free()),
        # whose FMU states went with it
        self._finalizer = weakref.finalize(self, _free_state, lib().ssx_state_free, handle,
                                           plan.sys, _fmu_instances(plan))

    def __repr__(self) -> str:
        shown = "closed" if self.closed else f"of system {self._plan.name!r}"
        return f"<SystemState {shown}>"

    @property
    def closed(self) -> bool:
        """Whether the state was freed (close())."""
        return not self._finalizer.alive

    def close(self) -> None:
        """Free the state now; using it afterwards raises StateError."""
        self._finalizer()

    def _handle_for(self, plan: EnginePlan) -> Any:
        """The engine's state, checked to belong to `plan` (the System's current engine
        system)."""
        if self.closed:
            raise StateError(f"system {plan.name!r}: the state was closed")
        if self._plan is not plan:
            raise StateError(f"system {plan.name!r}: the state was saved from another engine "
                             "system (another System, or this one before it was built again); "
                             "turn it into bytes (to_bytes) and read them with "
                             "state_from_bytes")
        return self._handle

    def to_bytes(self) -> bytes:
        """The state as bytes (the FMUs' serialized states within), which state_from_bytes of
        this System or of an identically built one reads back."""
        plan = self._plan
        handle = self._handle_for(plan)
        out = ffi.new("unsigned char **")
        size = ffi.new("size_t *")
        if lib().ssx_state_serialize(plan.sys, handle, out, size) != 0:
            raise state_error(plan)
        try:
            return bytes(ffi.buffer(out[0], size[0]))
        finally:
            lib().ssx_state_bytes_free(out[0])


def save_state(plan: EnginePlan) -> SystemState:
    """The state of the plan's engine system now."""
    handle = lib().ssx_state_save(plan.sys)
    if handle == ffi.NULL:
        raise state_error(plan)
    return SystemState(plan, handle)


def restore_state(plan: EnginePlan, state: SystemState) -> tuple[float, Termination | None]:
    """Put `state` back into the plan's engine system; the time and termination it holds."""
    if not isinstance(state, SystemState):
        raise StateError(f"system {plan.name!r}: restore_state takes a SystemState, not "
                         f"{type(state).__name__} (bytes become one through state_from_bytes)")
    if lib().ssx_state_restore(plan.sys, state._handle_for(plan)) != 0:
        raise state_error(plan)
    return float(lib().ssx_time(plan.sys)), read_termination(plan)


def state_from_bytes(plan: EnginePlan, data: bytes) -> SystemState:
    """A state of the plan's engine system read from to_bytes' bytes."""
    handle = lib().ssx_state_deserialize(plan.sys, ffi.from_buffer(data), len(data))
    if handle == ffi.NULL:
        raise state_error(plan)
    return SystemState(plan, handle)


def state_error(plan: EnginePlan) -> StateError:
    """The engine's last error as a StateError naming its component."""
    error = lib().ssx_last_error(plan.sys)
    names = list(plan.index)
    component = names[error.component] if 0 <= error.component < len(names) else None
    return StateError(ffi.string(error.message).decode(errors="replace"), component=component)


def _fmu_instances(plan: EnginePlan) -> list[FMUInstance]:
    instances = (getattr(c, "instance", None) for c in plan.components.values())
    return [instance for instance in instances if isinstance(instance, FMUInstance)]


def _free_state(free: Any, handle: Any, _system: Any, instances: Sequence[FMUInstance]) -> None:
    """The finalizer: `free` is ssx_state_free, looked up when the state was made."""
    if not any(instance.released() for instance in instances):
        free(handle)
