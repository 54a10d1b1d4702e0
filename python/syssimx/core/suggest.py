""""did you mean ...?" for a misspelled name: the close matches among the valid ones."""

from __future__ import annotations

import difflib
from collections.abc import Iterable


def close_matches(name: str, choices: Iterable[str], count: int = 3) -> list[str]:
    """Up to `count` valid names close to `name`, best first (a case-only difference first)."""
    choices = [str(c) for c in choices]
    same_case = [c for c in choices if c.lower() == name.lower() and c != name]
    close = difflib.get_close_matches(name, choices, n=count, cutoff=0.6)
    return list(dict.fromkeys([*same_case, *close]))[:count]


def did_you_mean(name: str, choices: Iterable[str]) -> str:
    """" (did you mean 'x'?)" (or "'x' or 'y'") when a valid name is close, else ""."""
    matches = close_matches(name, choices)
    if not matches:
        return ""
    return " (did you mean " + " or ".join(repr(m) for m in matches) + "?)"
