"""component.history: SysSimX's ComponentHistory over the samples the engine recorded."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np

from ..core.suggest import did_you_mean
from ..errors import UnknownNameError
from ..units import to_unit


class Recorded(Protocol):
    """What a history reads of its component (a CoSimComponent)."""

    name: str
    output_specs: Mapping[str, Any]

    def get_history_arrays(self) -> tuple[np.ndarray, dict[str, np.ndarray]]: ...

    def engine_outputs(self) -> list[str]: ...


@dataclass(frozen=True)
class PortHistory:
    """One output's samples: `time`, `values` (in `unit`)."""

    port_name: str
    time: np.ndarray
    values: np.ndarray
    unit: str | None = None

    def get_values(self, as_unit: str | None = None) -> np.ndarray:
        """The values, converted to `as_unit` (pint) when given."""
        if as_unit is None or self.unit is None:
            return self.values
        return (self.values * to_unit(self.unit)).to(to_unit(as_unit)).magnitude

    def to_dict(self, as_unit: str | None = None) -> dict[str, Any]:
        return {"time": self.time, "values": self.get_values(as_unit),
                "unit": as_unit or self.unit}

    def to_tuple(self, as_unit: str | None = None) -> tuple[np.ndarray, np.ndarray, str | None]:
        return self.time, self.get_values(as_unit), as_unit or self.unit

    def __len__(self) -> int:
        return len(self.time)


class ComponentHistory:
    """The outputs a component recorded in the system it runs in (copies of the engine's
    samples, taken when asked for), and its committed model switches."""

    def __init__(self, component: Recorded) -> None:
        self._component = component

    def get_all_histories(self) -> dict[str, PortHistory]:
        t, values = self._component.get_history_arrays()
        specs = self._component.output_specs
        return {name: PortHistory(name, t, column, specs[name].unit)
                for name, column in values.items()}

    def get_port_history(self, port_name: str) -> PortHistory:
        histories = self.get_all_histories()
        if port_name not in histories:
            raise UnknownNameError(f"{self._component.name}: no history for output {port_name!r}"
                                   f"{did_you_mean(port_name, histories)}; "
                           f"outputs: {sorted(histories)}")
        return histories[port_name]

    def to_arrays(self, port_names: list[str] | None = None,
                  units: dict[str, str] | None = None
                  ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """(time, {output: values}), values converted to `units[output]` when given."""
        histories = self.get_all_histories()
        names = list(histories) if port_names is None else port_names
        t = next(iter(histories.values())).time if histories else np.empty(0)
        return t, {n: self.get_port_history(n).get_values((units or {}).get(n))
                   for n in names}

    def to_dict(self, port_names: list[str] | None = None,
                units: dict[str, str] | None = None) -> dict[str, dict[str, Any]]:
        """{output: {"time", "values", "unit"}}."""
        names = list(self.get_all_histories()) if port_names is None else port_names
        return {n: self.get_port_history(n).to_dict((units or {}).get(n)) for n in names}

    @property
    def mode_switch_events(self) -> tuple[Any, ...]:
        """The model switches of a MultiComponent (empty for other components)."""
        return tuple(getattr(self._component, "switch_events", ()))

    def __len__(self) -> int:
        return len(self._component.engine_outputs())

    def __contains__(self, port_name: object) -> bool:
        return port_name in self._component.engine_outputs()
