"""TimeTable: a time column and named signal columns, read from what users hold signals in.

The sources are those of FMPy's `simulate_fmu(input=...)`: a numpy structured array whose first
field is the time, or a CSV file in FMPy's format (read by FMPy's own reader), and also a pandas
DataFrame whose first column is the time. A column's dtype says its kind: floating -> REAL,
integer -> INT, bool -> BOOL.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..core.port import PortType
from ..errors import ConfigurationError


@dataclass(frozen=True)
class TimeTable:
    """Times (float64) and, per column, its kind and values (float64, one per time)."""

    time: np.ndarray
    columns: dict[str, tuple[PortType, np.ndarray]]


def read_time_table(source: Any, where: str) -> TimeTable:
    """A TimeTable from a structured array, a DataFrame or an FMPy-format CSV path; `where`
    names the component in error messages."""
    if isinstance(source, str | Path):
        return _from_structured(_read_csv(Path(source), where), f"{where} ({source})")
    if hasattr(source, "to_records") and hasattr(source, "columns"):  # a pandas DataFrame
        return _from_structured(source.to_records(index=False), where)
    if isinstance(source, np.ndarray) and source.dtype.names is not None:
        return _from_structured(source, where)
    raise ConfigurationError(f"{where}: a time table is a numpy structured array, a pandas "
                             f"DataFrame or the path of a CSV file; got {type(source).__name__}")


def _read_csv(path: Path, where: str) -> np.ndarray:
    from fmpy.util import read_csv

    if not path.is_file():
        raise ConfigurationError(f"{where}: no CSV file {str(path)!r}")
    try:
        return read_csv(str(path))
    except Exception as error:  # FMPy's reader raises whatever the broken line causes
        reason = str(error) or type(error).__name__
        raise ConfigurationError(f"{where}: {path} is not a table in FMPy's CSV format (a "
                                 f"header line, then one line of numbers per time): "
                                 f"{reason}") from error


def _from_structured(array: np.ndarray, where: str) -> TimeTable:
    names = array.dtype.names or ()
    if len(names) < 2 or array.ndim != 1:
        raise ConfigurationError(f"{where}: a table is one row per time: a time column, then "
                                 f"at least one signal column; got fields {list(names)}")
    time = np.array(array[names[0]], dtype=np.float64)
    columns: dict[str, tuple[PortType, np.ndarray]] = {}
    for name in names[1:]:
        dtype = array.dtype[name]
        kind = _kind(dtype)
        if kind is None:
            raise ConfigurationError(f"{where}: column {name!r} has dtype {dtype}; a column "
                                     "holds one float, integer or bool per row")
        columns[name] = (kind, np.array(array[name], dtype=np.float64))
    return TimeTable(time, columns)


def _kind(dtype: np.dtype) -> PortType | None:
    if dtype.shape != ():
        return None
    if np.issubdtype(dtype, np.bool_):
        return PortType.BOOL
    if np.issubdtype(dtype, np.integer):
        return PortType.INT
    if np.issubdtype(dtype, np.floating):
        return PortType.REAL
    return None
