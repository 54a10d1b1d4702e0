"""Streaming a run to NetCDF (the classic format, 64-bit offset version, readable by xarray,
scipy, netCDF4 and every NetCDF tool): one unlimited dimension `sample`, a variable per value
(time, micro, then component.output, encoded where the format or a reader needs it: see
netcdf_names). A classic file stores the record variables interleaved, one record per sample,
so a block of samples is appended as it comes; the record count in the header is written when
the file is closed.

Written here from the format's specification (NetCDF Classic and 64-bit Offset Format), so
that it needs nothing beyond numpy.
"""

from __future__ import annotations

import struct
from pathlib import Path
from typing import IO

import numpy as np

from .netcdf_names import netcdf_name
from .writer import MICRO, TIME

_MAGIC = b"CDF\x02"  # 64-bit offset: files over 2 GiB
_NC_DIMENSION, _NC_VARIABLE, _NC_ATTRIBUTE = 0x0A, 0x0B, 0x0C
_NC_CHAR, _NC_INT, _NC_DOUBLE = 2, 4, 6
_ABSENT = struct.pack(">ii", 0, 0)
_NUMRECS_AT = 4  # bytes into the file


def _name(text: str) -> bytes:
    raw = text.encode("utf-8")
    return struct.pack(">i", len(raw)) + raw + b"\0" * (-len(raw) % 4)


def _attributes(name: str, written: str) -> bytes:
    """A variable's attributes: none, or `long_name`, the name itself where it is written
    encoded (see netcdf_names)."""
    if written == name:
        return _ABSENT
    text = name.encode("utf-8")
    return (struct.pack(">ii", _NC_ATTRIBUTE, 1) + _name("long_name") +
            struct.pack(">ii", _NC_CHAR, len(text)) + text + b"\0" * (-len(text) % 4))


class NetcdfWriter:
    def __init__(self) -> None:
        self._file: IO[bytes] | None = None
        self._record: np.dtype | None = None
        self._records = 0

    def open(self, path: Path, columns: list[str]) -> None:
        names = [TIME, MICRO, *columns]
        types = [_NC_DOUBLE, _NC_INT] + [_NC_DOUBLE] * len(columns)
        self._record = np.dtype([(name, ">i4" if kind == _NC_INT else ">f8")
                                 for name, kind in zip(names, types, strict=True)])
        header = bytearray(_MAGIC + struct.pack(">i", 0))
        header += struct.pack(">ii", _NC_DIMENSION, 1) + _name("sample") + struct.pack(">i", 0)
        header += _ABSENT  # no global attributes
        header += struct.pack(">ii", _NC_VARIABLE, len(names))
        # every variable's `begin` is its offset inside the first record, after the header
        entries = []
        for name, kind in zip(names, types, strict=True):
            size = 4 if kind == _NC_INT else 8
            written = netcdf_name(name)
            entries.append((_name(written) + struct.pack(">ii", 1, 0) +
                            _attributes(name, written) + struct.pack(">ii", kind, size), size))
        header_size = len(header) + sum(len(entry) + 8 for entry, _ in entries)
        offset = header_size
        for entry, size in entries:
            header += entry + struct.pack(">q", offset)
            offset += size
        self._file = open(path, "wb")
        self._file.write(bytes(header))
        self._records = 0

    def write(self, t: np.ndarray, micro: np.ndarray, values: np.ndarray) -> None:
        assert self._file is not None and self._record is not None, "open() first"
        block = np.empty(len(t), dtype=self._record)
        names = self._record.names
        block[names[0]] = t
        block[names[1]] = micro
        for k, name in enumerate(names[2:]):
            block[name] = values[:, k]
        self._file.write(block.tobytes())
        self._records += len(t)

    def close(self) -> None:
        if self._file is not None:
            self._file.seek(_NUMRECS_AT)
            self._file.write(struct.pack(">i", self._records))
            self._file.close()
            self._file = None
