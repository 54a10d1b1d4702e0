"""Monte Carlo members: parameter values drawn from distributions with one seeded generator."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from ..errors import ConfigurationError
from .members import ParameterTable, parameter_table

Sampler = Callable[[np.random.Generator, int], Any]


def draw(distributions: Mapping[str, Any], samples: int, seed: int | None) -> ParameterTable:
    """`samples` parameter sets. A distribution is a frozen scipy.stats distribution (anything
    with `rvs(size=, random_state=)`) or a function (generator, count) -> values. One
    numpy Generator seeded with `seed` draws the parameters in the order given, so the same
    seed gives the same members."""
    if isinstance(samples, bool) or not isinstance(samples, int) or samples < 1:
        raise ConfigurationError(f"samples must be a positive integer, got {samples!r}")
    generator = np.random.default_rng(seed)
    columns = {name: _draw_one(name, distribution, generator, samples)
               for name, distribution in distributions.items()}
    return parameter_table(columns, mode="zip")


def _draw_one(name: str, distribution: Any, generator: np.random.Generator,
              samples: int) -> np.ndarray:
    if hasattr(distribution, "rvs"):
        values = distribution.rvs(size=samples, random_state=generator)
    elif callable(distribution):
        values = distribution(generator, samples)
    else:
        raise ConfigurationError(f"{name}: a distribution is a frozen scipy.stats distribution "
                                 f"or a function (generator, count) -> values, got "
                                 f"{type(distribution).__name__} {distribution!r}")
    values = np.asarray(values).ravel()
    if values.shape != (samples,):
        raise ConfigurationError(f"{name}: the distribution gave {values.size} values for "
                                 f"{samples} samples")
    return values
