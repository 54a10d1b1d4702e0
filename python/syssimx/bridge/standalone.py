"""The private one-component system a component runs in when it is used on its own.

Components reach it here instead of importing syssimx.system, which builds on them: the
package, above both, registers how to make a System when it is imported."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol


class StandaloneSystem(Protocol):
    """What a component needs of the System it runs in on its own."""

    is_initialized: bool

    def add_component(self, component: Any) -> None: ...

    def initialize(self, t0: float = 0.0) -> None: ...

    def run(self, t0: float, tf: float, dt: float) -> Any: ...

    def restart_recording(self, t: float) -> None: ...


_SYSTEM_CLASS: list[Callable[[str], StandaloneSystem]] = []


def register_system_class(system_class: Callable[[str], StandaloneSystem]) -> None:
    """Called once by the syssimx package with what makes a System."""
    _SYSTEM_CLASS[:] = [system_class]


def standalone_system(component: Any) -> StandaloneSystem:
    """A new System holding only `component`."""
    system = _SYSTEM_CLASS[0](f"{component.name} (standalone)")
    system.add_component(component)
    return system
