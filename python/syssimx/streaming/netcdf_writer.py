"""Streaming a run to NetCDF-4 (an HDF5 file, readable by xarray, netCDF4 and h5py): one
unlimited dimension `sample`, a variable per value (its name component.output), time and micro
among them, grown block by block."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from .writer import MICRO, TIME


class NetcdfWriter:
    def __init__(self) -> None:
        self._file: Any = None
        self._names: list[str] = []
        self._length = 0

    def open(self, path: Path, columns: list[str]) -> None:
        try:
            import h5netcdf
        except ImportError as exc:
            raise ImportError("streaming to NetCDF needs h5netcdf: pip install "
                              "'syssimx[results]'") from exc
        self._file = h5netcdf.File(path, "w")
        self._file.dimensions = {"sample": None}
        self._file.create_variable(TIME, ("sample",), np.float64, chunks=(4096,))
        self._file.create_variable(MICRO, ("sample",), np.int32, chunks=(4096,))
        for name in columns:
            self._file.create_variable(name, ("sample",), np.float64, chunks=(4096,))
        self._names = list(columns)
        self._length = 0

    def write(self, t: np.ndarray, micro: np.ndarray, values: np.ndarray) -> None:
        assert self._file is not None, "open() first"
        start, end = self._length, self._length + len(t)
        self._file.resize_dimension("sample", end)
        self._file.variables[TIME][start:end] = t
        self._file.variables[MICRO][start:end] = micro
        for k, name in enumerate(self._names):
            self._file.variables[name][start:end] = values[:, k]
        self._length = end

    def close(self) -> None:
        if self._file is not None:
            self._file.close()
            self._file = None
