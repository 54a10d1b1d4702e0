"""SwitchRegions: which model of a MultiComponent is active, by the value of one signal.

Ordered breakpoints split the signal's range into regions, each naming a model. Each boundary
has a hysteresis band: leaving the region below a breakpoint takes the signal above
breakpoint + band, leaving the region above it takes it below breakpoint - band, so a signal
hovering at a breakpoint does not switch back and forth.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from itertools import pairwise
from typing import Any

from ..errors import ConfigurationError, ConfigurationTypeError


@dataclass(frozen=True)
class RegionBoundary:
    """Boundary `index` between region index and index + 1, at breakpoint, with its band."""

    index: int
    breakpoint: float
    band: float

    @property
    def lower_threshold(self) -> float:
        return self.breakpoint - self.band

    @property
    def upper_threshold(self) -> float:
        return self.breakpoint + self.band

    def threshold_for(self, region: int) -> float:
        """The threshold to cross from `region`: the band's far edge seen from that side."""
        return self.upper_threshold if region <= self.index else self.lower_threshold

    def target_region(self, region: int) -> int:
        """The region reached by crossing this boundary from the adjacent `region`."""
        if region == self.index:
            return self.index + 1
        if region == self.index + 1:
            return self.index
        raise ConfigurationError(f"boundary {self.index} does not border region {region}")


@dataclass(frozen=True, init=False)
class SwitchRegions:
    """key(wrapper) -> float, strictly increasing breakpoints, one model per region
    (len(modes) == len(breakpoints) + 1, neighbours different) and a band > 0 per boundary
    (one number for all) whose bands neither overlap nor touch."""

    key: Callable[[Any], float]
    modes: tuple[str, ...]
    boundaries: tuple[RegionBoundary, ...]

    def __init__(self, key: Callable[[Any], float], breakpoints: Sequence[float],
                 modes: Sequence[str], band: float | Sequence[float]) -> None:
        if not callable(key):
            raise ConfigurationTypeError("SwitchRegions: key must be a callable of the component")
        points = tuple(float(p) for p in breakpoints)
        names = tuple(modes)
        if len(names) < 2 or len(points) != len(names) - 1:
            raise ConfigurationError(f"SwitchRegions: {len(names)} modes need {len(names) - 1} "
                             f"breakpoints, got {len(points)} (at least two modes)")
        if not all(math.isfinite(p) for p in points) or \
                any(a >= b for a, b in pairwise(points)):
            raise ConfigurationError(f"SwitchRegions: breakpoints must be finite and strictly "
                             f"increasing, got {points}")
        if any(a == b for a, b in pairwise(names)):
            raise ConfigurationError(
                f"SwitchRegions: neighbouring regions use the same model: {names}")
        bands = (tuple(float(b) for b in band) if isinstance(band, Sequence)
                 else (float(band),) * len(points))
        if len(bands) != len(points) or not all(math.isfinite(b) and b > 0 for b in bands):
            raise ConfigurationError(f"SwitchRegions: one band > 0 per breakpoint, got {bands}")
        boundaries = tuple(RegionBoundary(i, p, b) for i, (p, b)
                           in enumerate(zip(points, bands, strict=True)))
        if any(a.upper_threshold >= b.lower_threshold
               for a, b in pairwise(boundaries)):
            raise ConfigurationError("SwitchRegions: the bands of neighbouring breakpoints overlap")
        object.__setattr__(self, "key", key)
        object.__setattr__(self, "modes", names)
        object.__setattr__(self, "boundaries", boundaries)

    @property
    def breakpoints(self) -> tuple[float, ...]:
        return tuple(b.breakpoint for b in self.boundaries)

    @property
    def bands(self) -> tuple[float, ...]:
        return tuple(b.band for b in self.boundaries)

    def initial_region(self, value: float) -> int:
        """The region holding `value` at initialization (by the breakpoints themselves)."""
        if not math.isfinite(value):
            raise ConfigurationError(f"SwitchRegions: the switching signal is not finite ({value})")
        return bisect_right(self.breakpoints, value)
