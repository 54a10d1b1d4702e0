"""result.events: the handled events in order, also readable the way SysSimX code reads them.

A list of EventRecord (`result.events[0].t`, `len(result.events)`, iteration), and, like
SysSimX's `{(component, event): [DenseTime, ...]}`, indexable by a (component, event) pair with
keys(), values(), items() and get().
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any, SupportsIndex, overload

from ..errors import UnknownNameError

if TYPE_CHECKING:
    from ..core.events import DenseTime
    from .event_record import EventRecord


class EventLog(list["EventRecord"]):
    """The events of a run in handling order; `log["P", "wall_hit"]` -> [DenseTime, ...]."""

    def __init__(self, events: Iterable[EventRecord] = ()) -> None:
        super().__init__(events)

    def _by_source(self) -> dict[tuple[str, str], list[DenseTime]]:
        histories: dict[tuple[str, str], list[DenseTime]] = {}
        for record in self:
            histories.setdefault((record.component, record.event), []).append(record.time)
        return histories

    @overload
    def __getitem__(self, key: SupportsIndex) -> EventRecord: ...
    @overload
    def __getitem__(self, key: slice) -> list[EventRecord]: ...
    @overload
    def __getitem__(self, key: tuple[str, str]) -> list[DenseTime]: ...

    def __getitem__(self, key: Any) -> Any:
        if isinstance(key, tuple):
            histories = self._by_source()
            if key not in histories:
                raise UnknownNameError(f"no event {key!r}; events: {sorted(histories)}")
            return histories[key]
        return super().__getitem__(key)

    def __contains__(self, item: object) -> bool:
        if isinstance(item, tuple):
            return item in self._by_source()
        return super().__contains__(item)

    def keys(self) -> list[tuple[str, str]]:
        """The (component, event) pairs that fired, in order of their first firing."""
        return list(self._by_source())

    def values(self) -> list[list[DenseTime]]:
        return list(self._by_source().values())

    def items(self) -> list[tuple[tuple[str, str], list[DenseTime]]]:
        return list(self._by_source().items())

    def get(self, key: tuple[str, str], default: Any = None) -> Any:
        return self._by_source().get(key, default)

    def trials(self) -> Any:
        """Every localization trial in a table (needs pandas): one row per trial, columns
        event (the index in this log), component, name, trial, t, a, b, value."""
        from ..extras import require

        pd = require("pandas", "EventLog.trials")
        rows = [(index, record.component, record.event, number, trial.t, trial.a, trial.b,
                 trial.value)
                for index, record in enumerate(self)
                for number, trial in enumerate(record.trials)]
        return pd.DataFrame(rows, columns=["event", "component", "name", "trial", "t", "a",
                                           "b", "value"])

    def _repr_html_(self) -> str:
        from .result_display import events_html

        return events_html(self, limit=None)
