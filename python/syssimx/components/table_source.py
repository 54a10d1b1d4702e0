"""TableSource: input signals from a time table, one output port per column, evaluated in C.

    u = TableSource("u", "signals.csv")       # or a structured array, a DataFrame
    system.add_component(u)
    system.add_connection(Connection("u", "torque", "P", "torque"))

Values follow FMPy's input signals exactly: the first row before the table, the last row after
it; real columns interpolate linearly, integer and boolean columns (and real columns named in
`hold`) hold the row on the left; at a repeated time stamp (a jump) the value on the right once
the run has started. No Python runs per step.

Timing: a component stepping from t reads the table at t under the Jacobi coupling (FMPy's
simulate_fmu sets its inputs so), and under Gauss-Seidel when it runs before the table; under
Gauss-Seidel after the table (the table feeds it without delay) it reads the table at t + dt.
FMPy also steps to each jump between its grid points (`event_times()`), as
`syssimx simulate --input` does; a System keeps its grid.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core.port import Port, PortSpec, PortType
from ..errors import ConfigurationError
from .base import CoSimComponent
from .time_table import TimeTable, read_time_table

if TYPE_CHECKING:
    from ..bridge.plan import EnginePlan


class TableSource(CoSimComponent):
    """A component whose outputs are the columns of a time table.

    `table` is a numpy structured array (first field: time), a pandas DataFrame (first column:
    time) or the path of a CSV file in FMPy's format. `units` gives REAL columns a unit,
    `hold` names REAL columns to hold between rows instead of interpolating (FMPy holds the
    inputs an FMU declares discrete)."""

    def __init__(self, name: str, table: Any, units: Mapping[str, str] | None = None,
                 hold: Iterable[str] = (), group: str | None = None) -> None:
        super().__init__(name, group=group)
        self.table: TimeTable = read_time_table(table, f"table {name!r}")
        units = dict(units or {})
        self.hold = frozenset(hold)
        for label, names in (("units", units), ("hold", self.hold)):
            unknown = sorted(set(names) - set(self.table.columns))
            if unknown:
                raise ConfigurationError(f"table {name!r}: {label} names no column {unknown[0]!r}"
                                         f"; columns: {list(self.table.columns)}")
        for column, (kind, _) in self.table.columns.items():
            if kind != PortType.REAL and (column in units or column in self.hold):
                raise ConfigurationError(f"table {name!r}: column {column!r} is {kind.name}; "
                                         "only REAL columns take a unit or a hold")
            self.output_specs[column] = PortSpec(column, kind, "out", units.get(column))
        self._sync_ports()

    def _make_port(self, spec: PortSpec) -> Port:
        if spec.type == PortType.EVENT:
            return Port(spec)
        return Port(spec, reader=lambda name=spec.name: self._engine_value(name))

    def _engine_value(self, name: str) -> float | int | bool:
        """The engine's current value of an output (the type's zero before any system runs)."""
        kind = self.output_specs[name].type
        value = 0.0 if self._binding is None else self._binding.plan.port_value(self, "out", name)
        return int(value) if kind == PortType.INT else bool(value) if kind == PortType.BOOL \
            else value

    def column_values(self, name: str) -> np.ndarray:
        """The values of an output's column, one per table row (float64)."""
        return self.table.columns[name][1]

    def event_times(self) -> np.ndarray:
        """Where the signals jump (FMPy's input events): every repeated time stamp, and each
        row at which a held column (integer, boolean or named in `hold`) changes value."""
        t = self.table.time
        times = set(t[:-1][np.diff(t) == 0].tolist())
        for name, (kind, values) in self.table.columns.items():
            if kind != PortType.REAL or name in self.hold:
                times.update(t[1:][np.diff(values) != 0].tolist())
        return np.array(sorted(times), dtype=np.float64)

    def can_rollback(self) -> bool:
        return True  # no state: the engine restores the outputs of every component

    def _add_to_plan(self, plan: EnginePlan) -> None:
        plan.add_table(self, self.table.time,
                       {n: self.column_values(n) for n in self.engine_outputs()}, set(self.hold))

    def _start(self, t0: float, tolerance: float | None = None) -> None:
        self._sync_ports()  # a table has no solver: the tolerance is not its business
        self.t = t0  # the engine evaluates the table at t0 itself
