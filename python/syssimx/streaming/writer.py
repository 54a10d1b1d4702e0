"""What a stream writer does: opened with the file and the names of a sample's values, handed
blocks of samples as the run goes on, closed when the run ends (whatever its outcome)."""

from __future__ import annotations

from pathlib import Path
from typing import Protocol

import numpy as np

# The first two columns of every file: the sample's time and superdense index (micro step 0,
# 1, ... at an event instant, -1 for a localization trial).
TIME = "time"
MICRO = "micro"


class StreamWriter(Protocol):
    def open(self, path: Path, columns: list[str]) -> None:
        """Start the file; columns names each value of a sample (component.output)."""

    def write(self, t: np.ndarray, micro: np.ndarray, values: np.ndarray) -> None:
        """Append n samples: times (n), micro steps (n, int32), values (n x columns). The
        arrays are valid only during the call: keep a copy, not them."""

    def close(self) -> None:
        """Finish the file: everything written is on disk."""
