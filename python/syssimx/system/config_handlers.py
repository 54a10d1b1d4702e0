"""Event handlers written in a description: restart the component at the event from its
outputs, e.g. `reinitialize: {theta0: theta, omega0: -0.8*omega}` (a bounce)."""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..components.base import CoSimComponent, EventHandler
from ..core.port import PortType
from ..errors import ConfigurationError

# "omega", "-omega", "0.8*omega", "-0.8 * omega"
_TERM = re.compile(r"^\s*(?:(?P<gain>[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*\*\s*|"
                   r"(?P<sign>[-+])\s*)?(?P<output>[A-Za-z_][\w.\[\],]*)\s*$")


@dataclass(frozen=True)
class Term:
    """gain * output, or a constant when output is None."""

    gain: float
    output: str | None = None

    def value(self, component: CoSimComponent) -> float:
        if self.output is None:
            return self.gain
        return self.gain * float(component.outputs[self.output].raw())


def parse_term(component: CoSimComponent, parameter: str, text: Any) -> Term:
    if isinstance(text, bool) or not isinstance(text, int | float | str):
        raise ConfigurationError(f"{parameter}: expected a number or an output expression, got "
                                 f"{text!r}")
    if not isinstance(text, str):
        return Term(float(text))
    match = _TERM.match(text)
    if match is None:
        raise ConfigurationError(f"{parameter}: {text!r} is not 'output', '-output' or "
                                 "'number*output'")
    output = match["output"]
    spec = component.output_specs.get(output)
    if spec is None or spec.type == PortType.EVENT:
        outputs = sorted(n for n, s in component.output_specs.items() if s.type != PortType.EVENT)
        raise ConfigurationError(f"{parameter}: {output!r} is not an output of "
                                 f"{component.name!r}; outputs: {outputs}")
    gain = float(match["gain"]) if match["gain"] else -1.0 if match["sign"] == "-" else 1.0
    return Term(gain, output)


def reinitialize_handler(component: CoSimComponent, restart: Mapping[str, Any]) -> EventHandler:
    """A handler that calls component.reinitialize(t, parameter=value, ...) with the values
    taken from the outputs at the event (in the outputs' units)."""
    unknown = sorted(set(restart) - set(component.parameters))
    if unknown:
        raise ConfigurationError(f"reinitialize: {component.name!r} has no parameter "
                                 f"{unknown[0]!r}; parameters: {sorted(component.parameters)}")
    terms = {str(p): parse_term(component, str(p), text) for p, text in restart.items()}

    def restart_from_outputs(comp: CoSimComponent, event_names: list[str], t: float) -> None:
        comp.reinitialize(t, **{p: term.value(comp) for p, term in terms.items()})

    return restart_from_outputs
