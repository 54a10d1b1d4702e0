"""Whether this Python can draw a system, and if not, what to install: what a notebook shows
under a system's text when it cannot show the picture."""

from __future__ import annotations

import importlib
import shutil

from ..extras import install_hint


def why_no_drawing() -> str | None:
    """None when graphviz and its `dot` program are there, else how to get the picture."""
    try:
        importlib.import_module("graphviz")
    except ImportError:
        return (f"no picture: drawing a system needs the graphviz package "
                f"({install_hint('graphviz')}) and Graphviz's dot program (apt install "
                "graphviz); describe() shows the structure as text")
    if shutil.which("dot") is None:
        return ("no picture: drawing a system needs Graphviz's dot program on PATH (apt "
                "install graphviz); describe() shows the structure as text")
    return None
