"""system.history: SysSimX's SystemHistory over what the engine recorded: the events, the
trajectories of ports and the CSV files of the samples."""

from __future__ import annotations

import weakref
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from ..core.events import DenseTime
from ..core.suggest import did_you_mean
from ..errors import ConfigurationError, UnknownNameError
from . import csv_export
from .event_record import EventRecord
from .recorded_events import RecordedEvents, as_recorded
from .results import recorded_units

if TYPE_CHECKING:
    from ..bridge.plan import EnginePlan


class HistorySource(Protocol):
    """What a history reads of the System that records it."""

    components: Mapping[str, Any]
    _plan: EnginePlan | None

    def get_history(self) -> dict[str, Any]: ...


class SystemHistory:
    """A system's record (SysSimX's `system.history`): its events, and through `system` (when
    given) its samples: trajectories of ports and CSV files."""

    def __init__(self, events: RecordedEvents | Sequence[EventRecord] = (),
                 system: HistorySource | None = None) -> None:
        self.recorded_events = as_recorded(events)
        self._events: list[EventRecord] | None = None  # made when first asked for
        # weak: the system holds its history, and a cycle would keep both until a collection
        self._system = weakref.ref(system) if system is not None else None

    @property
    def events(self) -> list[EventRecord]:
        """The events since initialize, in handling order."""
        if self._events is None:
            self._events = list(self.recorded_events.made())
        return self._events

    @events.setter
    def events(self, events: Sequence[EventRecord]) -> None:
        self._events = list(events)

    def get_event_history(self, component: str, event: str) -> list[DenseTime]:
        """The instants at which `component`'s indicator `event` fired."""
        return [e.time for e in self.events if (e.component, e.event) == (component, event)]

    def get_all_event_histories(self) -> dict[tuple[str, str], list[DenseTime]]:
        """The instants of every indicator that fired: {(component, event): [DenseTime]}."""
        histories: dict[tuple[str, str], list[DenseTime]] = {}
        for e in self.events:
            histories.setdefault((e.component, e.event), []).append(e.time)
        return histories

    def _recording_system(self) -> HistorySource:
        system = self._system() if self._system is not None else None
        if system is None or system._plan is None:
            raise ConfigurationError("this history has no samples: it belongs to no "
                                     "initialized system")
        return system

    def _recorded(self) -> tuple[dict[str, tuple[np.ndarray, dict[str, np.ndarray]]],
                                 dict[str, dict[str, str | None]]]:
        system = self._recording_system()
        recorded = system.get_history()
        return ({name: recorded[name] for name in system.components},
                recorded_units(system._plan))

    def get_port_trajectory(self, component: str, port: str, as_unit: str | None = None
                            ) -> tuple[np.ndarray, np.ndarray]:
        """(t, values) of one port; `as_unit` converts the values (pint) from the port's unit."""
        components = self._recording_system().components
        if component not in components:
            raise UnknownNameError(f"no component {component!r} in the history"
                                   f"{did_you_mean(component, components)}; components: "
                           f"{sorted(components)}")
        port_history = components[component].history.get_port_history(port)
        return port_history.time, port_history.get_values(as_unit)

    def save_csv(self, filepath: str | Path, component_names: Sequence[str] | None = None,
                 port_names: dict[str, list[str]] | None = None,
                 long_format: bool = False) -> Path:
        """Write the samples of the components (all when None), of the ports named in
        `port_names` (all of a component not named there): wide, "Comp.port" columns under a
        row of units (load_csv reads it), or the tidy long layout with `long_format`."""
        histories, units = self._recorded()
        names = list(component_names) if component_names is not None else list(histories)
        unknown = [n for n in names if n not in histories]
        if unknown:
            raise UnknownNameError(f"no component {unknown[0]!r} in the history"
                                   f"{did_you_mean(unknown[0], histories)}; components: "
                           f"{sorted(histories)}")
        chosen = {n: (histories[n][0], _chosen_ports(n, histories[n][1], port_names))
                  for n in names}
        target = Path(filepath)
        target.parent.mkdir(parents=True, exist_ok=True)
        if long_format:
            return csv_export.write_long(target, chosen, units,
                                         self._recording_system()._plan.history().micro())
        t = next(iter(chosen.values()))[0] if chosen else np.empty(0)
        signals = {f"{n}.{p}": v for n, (_, ports) in chosen.items() for p, v in ports.items()}
        signal_units = {f"{n}.{p}": units[n][p] for n, (_, ports) in chosen.items()
                        for p in ports}
        return csv_export.write_wide_with_units(target, t, signals, signal_units)

    @staticmethod
    def load_csv(filepath: str | Path) -> dict[str, dict[str, dict[str, Any]]]:
        """Read a file of save_csv (either layout) or of SimulationResult.to_csv (long):
        {component: {port: {"time": ndarray, "values": ndarray, "unit": str | None}}}."""
        return csv_export.read_samples(Path(filepath))


def _chosen_ports(component: str, ports: dict[str, np.ndarray],
                  port_names: dict[str, list[str]] | None) -> dict[str, np.ndarray]:
    wanted = (port_names or {}).get(component)
    if wanted is None:
        return ports
    unknown = [p for p in wanted if p not in ports]
    if unknown:
        raise UnknownNameError(f"component {component!r} recorded no port {unknown[0]!r}"
                               f"{did_you_mean(unknown[0], ports)}; ports: "
                       f"{sorted(ports)}")
    return {p: ports[p] for p in wanted}
