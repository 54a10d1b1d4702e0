"""The ensemble's progress bar on stderr (tqdm, as `System.run(progress=True)`): members done
and failed. No bar where stderr is not a terminal: a log gets no carriage-return frames."""

from __future__ import annotations

import sys
from typing import Any, TextIO


class ProgressBar:
    def __init__(self, total: int, enabled: bool = True, stream: TextIO | None = None) -> None:
        self.total, self.enabled = total, enabled
        self.stream = stream if stream is not None else sys.stderr
        self.done = self.failed = 0
        self._bar: Any = None
        if enabled:
            from tqdm import tqdm

            # disable=None: tqdm draws only on a terminal
            self._bar = tqdm(total=total, unit="member", file=self.stream, disable=None,
                             leave=True, dynamic_ncols=True)

    def advance(self, done: int, failed: int) -> None:
        """`done` more members finished, `failed` of them failed."""
        self.done += done
        self.failed += failed
        if self._bar is not None:
            if self.failed:
                self._bar.set_postfix_str(f"{self.failed} failed", refresh=False)
            self._bar.update(done)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None
