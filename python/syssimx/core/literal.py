"""Values typed on a command line: `true`/`false`, integers, reals, else the text itself."""

from __future__ import annotations


def literal(text: str) -> bool | int | float | str:
    """The value `text` spells: a boolean, an int, a float, or the text unchanged."""
    if text.lower() in ("true", "false"):
        return text.lower() == "true"
    for convert in (int, float):
        try:
            return convert(text)
        except ValueError:
            pass
    return text
