"""The one CSV writer of results, used by the API and by every command of the command line.

Three layouts, SysSimX's:

- long (tidy): ``component,port,time,value,unit``, one row per sample of each port;
- wide, FMPy's CSV (the interchange format FMPy's ``read_csv`` and ``write_csv`` use): ``time``
  then one column per port headed by its plain name, booleans as 0 and 1; on request each
  header says its unit, ``port [unit]`` (FMPy's reader then keeps the unit in the name);
- wide with a unit row (``SystemHistory.save_csv``): ``time,Comp.port,...`` then
  ``s,unit,...`` (``-`` without a unit), then the samples.

Numbers are written so that they read back exactly (Python's shortest round-trip form); an event
instant appears twice, as the samples before and after its handling: the long layout has a
``micro`` column (0 before, 1 after, ...) that tells them apart; FMPy's CSV repeats the time, as
FMPy's own results do.
"""

from __future__ import annotations

import csv
import itertools
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..atomic_file import atomic_path
from ..errors import ConfigurationError

LONG_HEADER = ("component", "port", "time", "micro", "value", "unit")
# the long layout of files written before it had a micro column
_LONG_HEADER_WITHOUT_MICRO = ("component", "port", "time", "value", "unit")
NO_UNIT = "-"  # the unit row's mark for a port without a unit

# {component: (t, {port: values})} and {component: {port: unit or None}}
Histories = Mapping[str, tuple[np.ndarray, Mapping[str, np.ndarray]]]
Units = Mapping[str, Mapping[str, str | None]]
# told the number of rows written since it was last called
Progress = Callable[[int], object]
_ROWS_PER_REPORT = 20_000


def write_long(path: str | Path, histories: Histories, units: Units, micro: np.ndarray,
               progress: Progress | None = None) -> Path:
    """Every port of every component in the tidy long layout; `micro` is the superdense index
    of each sample (the components share the samples' times). `progress(rows)` is told the
    rows written as the write goes on."""
    micros = _cells(micro)

    def rows() -> Iterable[Sequence[Any]]:
        for component, (t, ports) in histories.items():
            times = _cells(t)
            for port, values in ports.items():
                unit = units.get(component, {}).get(port) or ""
                for time, index, value in zip(times, micros, _cells(values), strict=True):
                    yield component, port, time, index, value, unit
    return _write(path, [LONG_HEADER], rows(), progress)


def write_wide(path: str | Path, t: np.ndarray, ports: Mapping[str, np.ndarray],
               units: Mapping[str, str | None] | None = None,
               progress: Progress | None = None) -> Path:
    """FMPy's CSV: time, then a column per port, ``port [unit]`` where `units` gives one;
    `progress` as write_long's."""
    units = units or {}
    header = ["time", *(f"{p} [{units[p]}]" if units.get(p) else p for p in ports)]
    columns = [_cells(np.asarray(v, dtype=np.int8) if np.asarray(v).dtype == np.bool_ else v)
               for v in ports.values()]  # FMPy's reader reads numbers only
    return _write(path, [header], zip(_cells(t), *columns, strict=True), progress)


def write_wide_with_units(path: str | Path, t: np.ndarray, signals: Mapping[str, np.ndarray],
                          units: Mapping[str, str | None]) -> Path:
    """Signals named ``component.port`` on one time axis, with a row of units under the names."""
    header = [["time", *signals], ["s", *(units.get(s) or NO_UNIT for s in signals)]]
    return _write(path, header, zip(_cells(t), *(_cells(v) for v in signals.values()),
                                                 strict=True))


def _cells(values: np.ndarray) -> list[Any]:
    """Python numbers: csv writes a float as its shortest form that reads back exactly, a
    boolean as True/False; bytes (a Binary port's) are written in hex, as FMI writes them."""
    cells = np.asarray(values).tolist()
    if cells and isinstance(cells[0], bytes):
        return [cell.hex() for cell in cells]
    return cells


def _write(path: str | Path, header: Sequence[Sequence[str]], rows: Iterable[Sequence[Any]],
           progress: Progress | None = None) -> Path:
    target = Path(path)
    with atomic_path(target) as temporary, temporary.open("w", newline="") as stream:
        writer = csv.writer(stream, lineterminator="\n")
        writer.writerows(header)
        if progress is None:
            writer.writerows(rows)
            return target
        rows = iter(rows)
        while batch := list(itertools.islice(rows, _ROWS_PER_REPORT)):
            writer.writerows(batch)
            progress(len(batch))
    return target


def read_samples(path: Path) -> dict[str, dict[str, dict[str, Any]]]:
    """A file in the long layout, the wide layout with a unit row, or FMPy's CSV (time, then a
    column per variable: "Comp.port" names a component, a plain name is a port of the
    component named by the file's stem), as
    {component: {port: {"time": ndarray, "values": ndarray, "unit": str | None}}}."""
    if not path.is_file():
        raise FileNotFoundError(f"no results file {str(path)!r}")
    with path.open(newline="") as stream:
        rows = list(csv.reader(stream))
    if rows and tuple(rows[0]) in (LONG_HEADER, _LONG_HEADER_WITHOUT_MICRO):
        return _read_long(rows[1:], micro=len(rows[0]) == len(LONG_HEADER))
    if len(rows) >= 2 and rows[0][:1] == ["time"] and rows[1][:1] == ["s"]:
        return _read_wide_with_units(rows)
    if rows and rows[0][:1] == ["time"]:  # FMPy's CSV: no unit row
        names = [n if "." in n else f"{path.stem}.{n}" for n in rows[0]]
        return _read_wide_with_units([names, ["s", *[NO_UNIT] * (len(names) - 1)], *rows[1:]])
    raise ConfigurationError(f"{path}: neither the long layout (header "
                             f"{','.join(LONG_HEADER)}), the wide layout with a unit row "
                             "(time,Comp.port,... then s,unit,...) nor FMPy's CSV (time,...)")


def _read_long(rows: list[list[str]], micro: bool) -> dict[str, dict[str, dict[str, Any]]]:
    cells: dict[tuple[str, str], tuple[list[str], list[str], str]] = {}
    for row in rows:
        component, port, time, value, unit = (*row[:3], *row[-2:]) if micro else row
        times, values, _ = cells.setdefault((component, port), ([], [], unit))
        times.append(time)
        values.append(value)
    data: dict[str, dict[str, dict[str, Any]]] = {}
    for (component, port), (times, values, unit) in cells.items():
        data.setdefault(component, {})[port] = {
            "time": np.array(times, dtype=float), "values": _column(values),
            "unit": unit or None}
    return data


def _read_wide_with_units(rows: list[list[str]]) -> dict[str, dict[str, dict[str, Any]]]:
    names, units, samples = rows[0], rows[1], rows[2:]
    columns = list(zip(*samples, strict=True)) if samples else [()] * len(names)
    time = np.array(columns[0], dtype=float)
    data: dict[str, dict[str, dict[str, Any]]] = {}
    for name, unit, values in zip(names[1:], units[1:], columns[1:], strict=True):
        component, _, port = name.partition(".")
        data.setdefault(component, {})[port] = {
            "time": time, "values": _column(list(values)),
            "unit": None if unit == NO_UNIT else unit}
    return data


def _column(cells: list[str]) -> np.ndarray:
    """Booleans where every cell is True or False, else numbers."""
    if cells and all(cell in ("True", "False") for cell in cells):
        return np.array([cell == "True" for cell in cells])
    return np.array(cells, dtype=float)
