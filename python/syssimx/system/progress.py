"""Progress of a run, reported by the engine's monitor (about every 50 ms of wall time, between
macro steps), never by a Python call per step.

`System.run(..., progress=...)` takes SysSimX's callback ``progress(t, tf)`` with the simulated
time reached, or True for a terminal bar (tqdm) that appears once a run has taken a second.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import Any, TextIO

from ..errors import ConfigurationError

ProgressCallback = Callable[[float, float], None]
BAR_DELAY = 1.0  # seconds of wall time before the bar appears: short runs stay silent


class ProgressBar:
    """A live bar over simulated time on `stream` (stderr by default), as a progress callback.
    tqdm is imported when the first report arrives."""

    def __init__(self, t0: float, stream: TextIO | None = None, delay: float = BAR_DELAY
                 ) -> None:
        self.t0, self.delay = t0, delay
        self.stream = stream
        self._bar: Any = None

    def __call__(self, t: float, tf: float) -> None:
        if self._bar is None:
            from tqdm import tqdm

            # the monitor already paces the reports (~50 ms): tqdm draws each one
            self._bar = tqdm(total=tf - self.t0, unit="s", delay=self.delay, leave=False,
                             mininterval=0.0, miniters=0,
                             file=self.stream if self.stream is not None else sys.stderr,
                             bar_format="{l_bar}{bar}| {n:.4g}/{total:.4g} s simulated "
                                        "[{elapsed}<{remaining}]")
        self._bar.update(t - self.t0 - self._bar.n)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None


class RunProgress:
    """The reports of one run: the monitor's times, in increasing order, then the end of the
    run exactly once."""

    def __init__(self, callback: ProgressCallback, tf: float) -> None:
        self.callback = callback
        self.tf = tf
        self.last = -float("inf")

    def report(self, t: float) -> None:
        if t > self.last:
            self.last = t
            self.callback(t, self.tf)

    def finish(self, t: float) -> None:
        """The run ended at t (tf unless a component stopped it): the final report."""
        try:
            if t != self.last:
                self.report(t)
        finally:
            self.close()

    def close(self) -> None:
        if isinstance(self.callback, ProgressBar):
            self.callback.close()


def run_progress(progress: bool | ProgressCallback | None, system: str, t0: float,
                 tf: float) -> RunProgress | None:
    """What `progress` asks for: nothing (None, False), a bar (True) or the user's callback."""
    if progress is None or progress is False:
        return None
    if progress is True:
        return RunProgress(ProgressBar(t0), tf)
    if not callable(progress):
        raise ConfigurationError(f"{system}: progress must be True, False, None or a callable "
                                 f"progress(t, tf), got {progress!r}")
    return RunProgress(progress, tf)
