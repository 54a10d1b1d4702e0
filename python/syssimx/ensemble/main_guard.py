"""A script that starts worker processes must keep its top-level work under
`if __name__ == "__main__":`. Worker processes are started by "spawn": each imports the user's
script again, and without the guard runs the sweep again inside the worker, which fails in
hundreds of lines of Dask and multiprocessing tracebacks. This check finds the missing guard
before any process starts and says how to write it."""

from __future__ import annotations

import ast
import sys
from pathlib import Path
from types import FrameType

from ..errors import ConfigurationError

GUARD = 'if __name__ == "__main__":'


class MissingMainGuardError(ConfigurationError):
    """An ensemble that starts worker processes is run at the top level of a script."""


def check_main_guard(function: str) -> None:
    """Raise MissingMainGuardError when `function` (sweep, monte_carlo) is reached from the
    top level of the `__main__` script, outside `if __name__ == "__main__":`."""
    frame = _script_frame()
    if frame is None:
        return
    path = Path(frame.f_code.co_filename)
    try:
        tree = ast.parse(path.read_text(), str(path))
    except (OSError, SyntaxError, ValueError):
        return  # no source to judge: the workers will tell
    line = frame.f_lineno
    for statement in tree.body:
        end = statement.end_lineno or statement.lineno
        if statement.lineno <= line <= end:
            if _is_guard(statement):
                return
            break
    raise MissingMainGuardError(
        f"{function}() is run at the top level of {path.name} (line {line}): its worker "
        f"processes import {path.name} again and would start {function}() again. Put the code "
        f"that runs it under the guard:\n\n    {GUARD}\n        result = {function}(...)\n")


def _script_frame() -> FrameType | None:
    """The frame of the `__main__` script's module code on the current call stack: the
    outermost frame whose globals are __main__'s, when __main__ is a file (not a notebook,
    not `python -c`)."""
    main = sys.modules.get("__main__")
    if main is None or getattr(main, "__file__", None) is None:
        return None
    frame: FrameType | None = sys._getframe(1)
    found = None
    while frame is not None:
        if frame.f_code.co_name == "<module>" and frame.f_globals is vars(main):
            found = frame
        frame = frame.f_back
    return found


def _is_guard(statement: ast.stmt) -> bool:
    """`if __name__ == "__main__":` (either side of the comparison)."""
    if not isinstance(statement, ast.If) or not isinstance(statement.test, ast.Compare):
        return False
    test = statement.test
    sides = [test.left, *test.comparators]
    names = [s for s in sides if isinstance(s, ast.Name) and s.id == "__name__"]
    constants = [s for s in sides if isinstance(s, ast.Constant) and s.value == "__main__"]
    return len(test.ops) == 1 and isinstance(test.ops[0], ast.Eq) and bool(names) \
        and bool(constants)
