"""Writing a run to disk while it runs: one writer per file format, each handed the samples the
history keeps in blocks, so that a run larger than memory keeps every sample.

`open_writer(path)` chooses the writer by the file's suffix: .csv, .parquet, .nc (NetCDF). A
writer of your own is any object with open(path, columns),
write(t, micro, values) and close() (see writer.StreamWriter).
"""

from __future__ import annotations

from pathlib import Path

from .writer import StreamWriter


def open_writer(path: str | Path) -> StreamWriter:
    """The writer for path's format, not yet opened."""
    suffix = Path(path).suffix.lower()
    if suffix == ".csv":
        from .csv_writer import CsvWriter

        return CsvWriter()
    if suffix == ".parquet":
        from .parquet_writer import ParquetWriter

        return ParquetWriter()
    if suffix == ".nc":
        from .netcdf_writer import NetcdfWriter

        return NetcdfWriter()
    raise ValueError(f"cannot stream a run to {path}: the suffix {suffix!r} names no format "
                     "syssimx writes (.csv, .parquet, .nc)")


__all__ = ["StreamWriter", "open_writer"]
