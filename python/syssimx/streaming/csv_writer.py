"""Streaming a run to CSV: one header line (time, micro, then component.output, quoted where a
name holds a comma, a quote or a line break), one line per sample, every float written with 17
significant digits so that reading it back gives the same doubles."""

from __future__ import annotations

import csv
from pathlib import Path
from typing import IO

import numpy as np

from .writer import MICRO, TIME


class CsvWriter:
    def __init__(self) -> None:
        self._file: IO[str] | None = None

    def open(self, path: Path, columns: list[str]) -> None:
        self._file = open(path, "w", encoding="utf-8", newline="")
        # quoted as the csv module quotes: a port named "a[1,2]" stays one column
        csv.writer(self._file, lineterminator="\n").writerow([TIME, MICRO, *columns])

    def write(self, t: np.ndarray, micro: np.ndarray, values: np.ndarray) -> None:
        assert self._file is not None, "open() first"
        block = np.column_stack([t, micro.astype(np.float64), values])
        formats = ["%.17g", "%d"] + ["%.17g"] * values.shape[1]
        np.savetxt(self._file, block, fmt=formats, delimiter=",")

    def close(self) -> None:
        if self._file is not None:
            self._file.close()
            self._file = None
