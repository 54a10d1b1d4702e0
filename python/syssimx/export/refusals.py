"""What cannot go into an exported FMU's binary: anything of the system that runs Python."""

from __future__ import annotations

from typing import Any

from ..components.base import CoSimComponent
from ..components.fmu import FMUComponent
from ..errors import ConfigurationError


def python_parts(system: Any) -> list[str]:
    """Each part of `system` that runs Python, named (empty when none does); the system is
    compiled (its plan written) first."""
    parts: list[str] = []
    for component in system.components.values():
        if type(component)._add_to_plan is CoSimComponent._add_to_plan:
            parts.append(f"Python component {component.name!r} "
                         f"({type(component).__name__})")
            continue
        for event, indicator in component.event_indicators.items():
            if indicator.variable is None:
                parts.append(f"Python event indicator {component.name}.{event}")
        if not isinstance(component, FMUComponent):
            continue
        hooks = component._python_hooks(engine_steps=True)
        if "handle_events" in hooks:
            inputs = ", ".join(sorted(component.event_handlers)) or "its events"
            parts.append(f"Python event handler of {component.name!r} ({inputs})")
        overridden = sorted(hooks - {"handle_events"})
        if overridden:
            parts.append(f"Python hooks of {component.name!r} ({type(component).__name__} "
                         f"overrides {', '.join(overridden)})")
    for observer in system._observers:
        parts.append(f"Python observer {type(observer).__name__}")
    return parts


def refuse_python(system: Any) -> None:
    """ConfigurationError naming every part of `system` that runs Python, if any does."""
    parts = python_parts(system)
    if parts:
        raise ConfigurationError(
            f"{system.name}: cannot be exported as an FMU, whose binary runs no Python; "
            f"these parts run Python: {'; '.join(parts)}")
