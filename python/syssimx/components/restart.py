"""Reinitialize: an event handler described once, not written in Python.

`Reinitialize(theta0="theta", omega0="-omega")` restarts the component at the event from its
start values, with those parameters taken from its outputs at the event (each value a number,
"output", "-output" or "gain*output", in the output's unit). Added with add_event_handler like
any handler. On a plain FMUComponent the engine runs it (ssx_set_restart_handler): no Python
per event, and the FMU instance is reset, not made anew. Anywhere else (a component class of
the user's, other handlers on the component) it is called like a Python handler, with the same
values.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

from ..core.events import OWN_EVENTS
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

    def value(self, component: Any) -> float:
        if self.output is None:
            return self.gain
        return self.gain * float(component.outputs[self.output].raw())


def parse_term(component: Any, parameter: str, text: Any) -> Term:
    """A number, or "output", "-output", "gain*output" naming an output of `component`."""
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


class Reinitialize:
    """Restart at the event with parameters from the outputs (see the module's description)."""

    def __init__(self, **values: float | str) -> None:
        self.values = dict(values)

    def __repr__(self) -> str:
        return "Reinitialize(" + ", ".join(f"{p}={v!r}" for p, v in self.values.items()) + ")"

    def terms(self, component: Any) -> dict[str, Term]:
        """Each parameter's term, checked against `component` (ConfigurationError names what is
        wrong)."""
        unknown = sorted(set(self.values) - set(component.parameters))
        if unknown:
            raise ConfigurationError(f"reinitialize: {component.name!r} has no parameter "
                                     f"{unknown[0]!r}; parameters: "
                                     f"{sorted(component.parameters)}")
        return {p: parse_term(component, p, text) for p, text in self.values.items()}

    def __call__(self, component: Any, event_names: list[str], t: float) -> None:
        # a component's own events reach it at the communication point after them: it
        # restarts where it stands, as the engine's restart does
        at = component.t if OWN_EVENTS in event_names else t
        component.reinitialize(at, **{p: term.value(component)
                                      for p, term in self.terms(component).items()})
