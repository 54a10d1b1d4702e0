"""`syssimx simulate --input`: a CSV of input signals in FMPy's format, connected to the FMU's
inputs, and FMPy's communication points around the signals' events."""

from __future__ import annotations

import itertools
import math
import sys
import time
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core.port import PortType
from .common import CommandError

if TYPE_CHECKING:
    from ..components.table_source import TableSource

# a stretch of regular steps is run in pieces of this many steps, the clock (--timeout) looked
# at every _DEADLINE_CHECKS points walked
_STRETCH_POINTS = 100_000
_DEADLINE_CHECKS = 4096
# the numpy type FMPy casts an input column to, by the input's type
_TABLE_DTYPES = {PortType.REAL: np.float64, PortType.INT: np.int32, PortType.BOOL: np.bool_}


def communication_points(t0: float, tf: float, dt: float, events: Iterable[float]
                         ) -> Iterator[float]:
    """FMPy's steps for an FMU that can vary its step: the grid t0 + k*dt plus every input
    event between grid points (one within 1e-9 relative of a grid point is that point), made
    one at a time: a long run holds none of them in memory."""
    upcoming_events, k = sorted(events), 0
    t, regular_steps = t0, 0
    yield t
    while not (t > tf or math.isclose(t, tf)):
        regular = t0 + (regular_steps + 1) * dt
        while k < len(upcoming_events) and (upcoming_events[k] <= t
                                            or math.isclose(upcoming_events[k], t)):
            k += 1
        upcoming = upcoming_events[k] if k < len(upcoming_events) else math.inf
        step_end = upcoming if regular > upcoming and not math.isclose(regular, upcoming) \
            else regular
        t = tf if step_end > tf and not math.isclose(step_end, tf) else step_end
        yield t
        regular_steps += math.isclose(t, regular)


def run_through(system: Any, points: Iterable[float], dt: float,
                timeout: float | None = None) -> Any:
    """Runs through the communication points: stretches of regular steps of dt in a run each
    (of up to _STRETCH_POINTS steps), every step off that grid (to or from an input event, to
    the stop time) in a run of its own; stops when a component terminates. `timeout` (wall
    seconds) covers all the runs, and the walk through the points between them."""
    from ..errors import SimulationTimeoutError

    deadline = None if timeout is None else time.monotonic() + timeout

    def run(t0: float, tf: float, step: float) -> Any:
        left = None if deadline is None else max(deadline - time.monotonic(), 1e-6)
        return system.run(t0, tf, step, timeout=left)

    points = iter(points)
    start = last = next(points)
    result, stretch = None, 0
    for previous, point in itertools.pairwise(itertools.chain([start], points)):
        last = point
        if math.isclose(point - previous, dt):
            stretch += 1
            if stretch % _STRETCH_POINTS == 0:  # run what is walked: --timeout and Ctrl-C see it
                result = run(start, point, dt)
                if result.termination is not None:
                    return result
                start = point
            elif deadline is not None and stretch % _DEADLINE_CHECKS == 0 \
                    and time.monotonic() >= deadline:
                raise SimulationTimeoutError(f"the run exceeded timeout={timeout} s of wall "
                                             f"time at t={start:.12g}", time=start)
            continue
        stretch = 0
        if previous > start:
            result = run(start, previous, dt)
            if result.termination is not None:
                return result
        result = run(previous, point, point - previous)
        if result.termination is not None:
            return result
        start = point
    if last > start:
        result = run(start, last, dt)
    return result


def connect_input(system: Any, component: Any, csv_path: Path) -> TableSource | None:
    """A table source from the CSV file, its columns connected to the inputs of the same name;
    each column is read as the input's type, held where FMPy holds it (non-continuous)."""
    from .. import Connection, TableSource
    from ..components.time_table import read_time_table

    table = read_time_table(csv_path, "--input")
    inputs = {n: s for n, s in component.input_specs.items() if s.type in _TABLE_DTYPES}
    used = [name for name in table.columns if name in inputs]
    ignored = [name for name in table.columns if name not in inputs]
    if ignored:
        print(f"syssimx: warning: {csv_path}: {', '.join(ignored)} "
              f"{'names' if len(ignored) == 1 else 'name'} no input of {component.name}; "
              "ignored", file=sys.stderr)
    if not used:
        return None
    columns = [("time", np.float64), *((n, _TABLE_DTYPES[inputs[n].type]) for n in used)]
    signals = np.empty(len(table.time), dtype=columns)
    signals["time"] = table.time
    for name in used:
        values, kind = table.columns[name][1], inputs[name].type
        if kind == PortType.REAL:
            signals[name] = values
        else:  # FMPy casts the column to the input's C int (truncating); a boolean is non-zero
            if kind == PortType.INT:
                _check_integer_column(csv_path, name, table.time, values)
            truncated = values.astype(np.int32)
            signals[name] = truncated if kind == PortType.INT else truncated != 0
    hold = [n for n in used if inputs[n].type == PortType.REAL
            and component.info.variables[n].variability in ("discrete", "tunable")]
    source = TableSource(csv_path.name, signals, hold=hold)  # numbers in the inputs' units
    system.add_component(source)
    for name in used:
        system.add_connection(Connection(source.name, name, component.name, name))
    return source


def _check_integer_column(csv_path: Path, name: str, time: np.ndarray, values: np.ndarray
                          ) -> None:
    """An Integer input takes C ints (an FMI 3.0 UInt32 or 64-bit input too): a value beyond
    them is refused, not wrapped."""
    limits = np.iinfo(np.int32)
    outside = np.flatnonzero((values < limits.min) | (values > limits.max))
    if len(outside):
        k = int(outside[0])
        raise CommandError(f"--input {csv_path}: column {name!r} holds {values[k]:.17g} at "
                           f"t = {float(time[k])!r}, outside the range of syssimx's Integer ports "
                           f"({limits.min}..{limits.max})")
