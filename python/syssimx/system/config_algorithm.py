"""The `algorithm` entry of a description: {type: jacobi|gauss_seidel|hybrid|ijcsa, options}.

A hybrid algorithm's coupling (`coupling` or SysSimX's `gauss_seidel_algorithm`) is a type name
or a mapping of the same form. A coupling's `step_control` is a mapping of StepControl's options
(`{rtol: 1e-5, atol: 1e-5, rollback: false}`); `{}` takes every default."""

from __future__ import annotations

from typing import Any

from .algorithm_table import ALGORITHM_NAMES, algorithm_class
from .algorithms import Algorithm, HybridAlgorithm, StepControl
from .config_source import Source, quoted

COUPLING_KEYS = ("coupling", "gauss_seidel_algorithm")


def build_algorithm(source: Source, entry: Any, label: str = "algorithm") -> Algorithm:
    if isinstance(entry, str):
        entry = {"type": entry}
    if not isinstance(entry, dict):
        raise source.error(label, f"must be a mapping with a 'type', got {quoted(entry)}", entry)
    kind = entry.get("type")
    if kind not in ALGORITHM_NAMES:
        raise source.error(label, f"unknown type {kind!r}; types: {sorted(ALGORITHM_NAMES)}", entry)
    options = {k: v for k, v in entry.items() if k != "type"}
    if kind == "hybrid":
        for key in COUPLING_KEYS:
            if key in options:
                options[key] = build_algorithm(source, options[key], f"{label}.{key}")
                if isinstance(options[key], HybridAlgorithm):
                    raise source.error(f"{label}.{key}", "the coupling of a hybrid algorithm "
                                       "is jacobi, gauss_seidel or ijcsa", entry)
    try:
        if isinstance(options.get("step_control"), dict):
            options["step_control"] = StepControl(**options["step_control"])
        algorithm = algorithm_class(kind)(**options)
        algorithm.validate()
    except (TypeError, ValueError) as exc:
        raise source.error(label, f"invalid options for {kind!r}: {exc}", entry) from exc
    return algorithm
