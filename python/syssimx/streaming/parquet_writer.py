"""Streaming a run to Parquet (pyarrow, the writer pandas uses): one row group per block, a
float64 column per value, time and micro first."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from .writer import MICRO, TIME


class ParquetWriter:
    def __init__(self, compression: str = "snappy") -> None:
        self.compression = compression
        self._writer: Any = None
        self._schema: Any = None

    def open(self, path: Path, columns: list[str]) -> None:
        try:
            import pyarrow as pa
            import pyarrow.parquet as pq
        except ImportError as exc:
            raise ImportError("streaming to Parquet needs pyarrow: pip install "
                              "'syssimx-engine[results]'") from exc
        fields = [pa.field(TIME, pa.float64()), pa.field(MICRO, pa.int32())]
        fields += [pa.field(name, pa.float64()) for name in columns]
        self._schema = pa.schema(fields)
        self._writer = pq.ParquetWriter(path, self._schema, compression=self.compression)

    def write(self, t: np.ndarray, micro: np.ndarray, values: np.ndarray) -> None:
        import pyarrow as pa

        assert self._writer is not None, "open() first"
        # pyarrow copies what it does not own: the block may be reused after this call
        arrays = [pa.array(t), pa.array(micro)]
        arrays += [pa.array(np.ascontiguousarray(values[:, k])) for k in range(values.shape[1])]
        self._writer.write_table(pa.Table.from_arrays(arrays, schema=self._schema))

    def close(self) -> None:
        if self._writer is not None:
            self._writer.close()
            self._writer = None
