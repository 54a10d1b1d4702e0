"""`syssimx sweep`: the command line's front-end to sweep."""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import sys
from pathlib import Path
from typing import Any, TextIO

from ..atomic_file import write_or_fallback
from ..errors import ConfigurationError, SimulationError
from ..partial_results import run_keeping_partial
from .api import sweep
from .members import Scalar, parse_values
from .system_source import SYSTEM_FILE_SUFFIXES, ShippedFunction, system_source


def parameter_values(text: str) -> tuple[str, list[Scalar]]:
    """argparse type of --param: "Component.parameter=VALUES"."""
    name, equals, values = text.partition("=")
    if not equals or "." not in name.strip(".") or name.startswith("."):
        raise argparse.ArgumentTypeError(f"expected Component.parameter=VALUES, got {text!r}")
    try:
        return name.strip(), parse_values(values)
    except ConfigurationError as error:
        raise argparse.ArgumentTypeError(f"{name.strip()}: {error}") from None


def run_sweep(args: argparse.Namespace, out: TextIO) -> None:
    """Run the sweep the arguments describe, write the results, list the failed members."""
    system = resolve_system(args.system)
    if isinstance(system, str):  # a system file: its classes come from the allowed modules
        system = system_source(system, tuple(args.allowed_modules or ()))
    result, interrupted = run_keeping_partial(lambda: sweep(
        system, dict(args.parameters), mode=args.mode, t0=args.start_time,
        tf=args.stop_time, dt=args.step_size, scheduler=args.scheduler, workers=args.workers,
        member_timeout=args.member_timeout, progress=not args.no_progress))
    if args.output is not None:
        write_or_fallback(args.output, result.write)
        out.write(f"wrote {len(result)} members to {args.output}\n")
    if interrupted is not None:
        raise interrupted
    failed = result.failed
    out.write(f"{len(result)} members, {len(result) - len(failed)} ok, {len(failed)} failed, "
              f"in {result.wall_time:.3g} s\n")
    for member in failed:
        values = ", ".join(f"{name}={value!r}" for name, value in member.parameters.items())
        out.write(f"member {member.index} ({values}) failed: {member.error}\n")
    if failed:
        raise SimulationError(f"{len(failed)} of {len(result)} members failed (listed above)")


def resolve_system(text: str) -> Any:
    """A system file path, or the function MODULE:FUNCTION / FILE.py:FUNCTION names."""
    if Path(text).suffix.lower() in SYSTEM_FILE_SUFFIXES:
        return text
    module_name, colon, function_name = text.rpartition(":")
    if not colon or not module_name or not function_name:
        suffixes = ", ".join(SYSTEM_FILE_SUFFIXES)
        raise ConfigurationError(f"{text!r} is neither a system file ({suffixes}) nor "
                                 "MODULE:FUNCTION or FILE.py:FUNCTION")
    from_file = module_name.endswith(".py")
    module = _load_file(Path(module_name)) if from_file \
        else importlib.import_module(module_name)
    function = getattr(module, function_name, None)
    if not callable(function):
        raise ConfigurationError(f"{text}: {module_name} has no function {function_name!r}")
    # the workers need not have the file: the function travels by value
    return ShippedFunction.of(function) if from_file else function


def _load_file(path: Path) -> Any:
    if not path.is_file():
        raise ConfigurationError(f"{path}: no such Python file")
    name = f"syssimx_sweep_{path.stem}"
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module
