"""The command line's entry point: one parser with a subcommand per module."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from .. import __version__
from ..output_check import check_command_outputs
from . import describe, fmu_list, info, run, simulate, sweep

COMMANDS = (info, fmu_list, simulate, run, describe, sweep)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line with ``argv`` (default: sys.argv[1:]); returns the exit code."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exit_request:  # argparse has printed usage or help already
        return int(exit_request.code or 0)
    try:
        check_command_outputs(args)  # before anything runs: results are never computed in vain
        args.run(args, sys.stdout)
    except KeyboardInterrupt as stop:  # what was finished has been written by the command
        print(f"syssimx: interrupted{': ' + str(stop) if str(stop) else ''}", file=sys.stderr)
        return 130
    except Exception as error:  # the command line shows messages, never tracebacks
        print(f"syssimx: error: {_describe(error, args)}", file=sys.stderr)
        return 1
    return 0


def _describe(error: Exception, args: argparse.Namespace) -> str:
    """The error's message; one that has none still says what failed and on which file."""
    if str(error).strip():
        return str(error)
    subject = f" {args.fmu}" if getattr(args, "fmu", None) else ""
    return f"{type(error).__name__} (with no message) in 'syssimx {args.command}{subject}'"


def build_parser() -> argparse.ArgumentParser:
    """The parser of the `syssimx` command line, one subcommand per module of COMMANDS (also
    what the documentation's command-line reference is generated from)."""
    parser = argparse.ArgumentParser(
        prog="syssimx",
        description="Hybrid co-simulation of FMI 1.0, 2.0 and 3.0 FMUs (Co-Simulation and "
                    "Model Exchange).",
    )
    parser.add_argument("--version", action="version", version=f"syssimx {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for command in COMMANDS:
        command.add_command(commands)
    return parser
