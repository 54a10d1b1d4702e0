"""The export map (resources/export.map): which exported value reference is which member port
or parameter, read by the FMU's binary (src/export/export_map.h describes the format)."""

from __future__ import annotations

from collections.abc import Sequence

from .selection import ExportedVariable

NAME_LENGTH = 900  # characters (UTF-8: at most 3600 bytes) of a name in the map, whose lines
# src/export/export_map.c reads up to 4096 bytes


def export_map(token: str, step_size: float | None,
               variables: Sequence[ExportedVariable]) -> str:
    """The map's text; step_size None: each doStep is one communication step of the system."""
    lines = ["syssimx-export 1", f'token "{token}"', f"step {float(step_size or 0.0)!r}"]
    # the name, the rest of its line, is for the binary's messages only: one line, cut to fit
    # the binary's line bound
    lines += [f"variable {v.value_reference} {v.role} {v.component} {v.index} {v.value_type} "
              f"{float('nan') if v.start is None else float(v.start)!r} "
              + " ".join(v.name.splitlines())[:NAME_LENGTH] for v in variables]
    return "\n".join(lines) + "\n"
