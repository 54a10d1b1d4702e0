"""Event handlers written in a description: restart the component at the event from its
outputs, e.g. `reinitialize: {theta0: theta, omega0: -0.8*omega}` (a bounce), run by the
engine where it can (components/restart.py)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..components.base import CoSimComponent
from ..components.restart import Reinitialize


def reinitialize_handler(component: CoSimComponent, restart: Mapping[str, Any]) -> Reinitialize:
    """A handler that restarts the component at t with the parameters taken from the outputs
    at the event (in the outputs' units); checked now."""
    handler = Reinitialize(**{str(p): text for p, text in restart.items()})
    handler.terms(component)
    return handler
