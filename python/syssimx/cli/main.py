"""The command line's entry point: one parser with a subcommand per module."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from .. import __version__
from ..core.suggest import did_you_mean
from ..output_check import check_command_outputs
from . import describe, export, fmu_list, info, run, simulate, sweep

COMMANDS = (info, fmu_list, simulate, run, describe, sweep, export)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line with ``argv`` (default: sys.argv[1:]); returns the exit code."""
    parser = build_parser()
    try:
        args, unknown = parser.parse_known_args(argv)
        if unknown:  # the subcommand's usage, not the top level's, with the close options
            command_parser = getattr(args, "command_parser", parser)
            command_parser.error(_unrecognized(command_parser, unknown))
    except SystemExit as exit_request:  # argparse has printed usage or help already
        return int(exit_request.code or 0)
    try:
        check_command_outputs(args)  # before anything runs: results are never computed in vain
        args.run(args, sys.stdout)
    except KeyboardInterrupt as stop:  # what was finished has been written by the command
        print(f"syssimx: interrupted{': ' + str(stop) if str(stop) else ''}", file=sys.stderr)
        return 130
    except MemoryError:  # its message is empty, or a C extension's unrelated one
        print(f"syssimx: error: out of memory in 'syssimx {args.command}': the run or its "
              "results need more memory than this process may use; shorten the run "
              "(--stop-time), record less (--output-interval) or allow more memory",
              file=sys.stderr)
        return 1
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


def _unrecognized(parser: argparse.ArgumentParser, unknown: list[str]) -> str:
    message = f"unrecognized arguments: {' '.join(unknown)}"
    options = [o for action in parser._actions for o in action.option_strings]
    for word in unknown:
        if word.startswith("--"):
            message += did_you_mean(word.split("=")[0], options)
    return message


def build_parser() -> argparse.ArgumentParser:
    """The parser of the `syssimx` command line, one subcommand per module of COMMANDS (also
    what the documentation's command-line reference is generated from)."""
    parser = argparse.ArgumentParser(
        prog="syssimx",
        description="Hybrid co-simulation of FMUs (FMI 1.0, 2.0 and 3.0, Co-Simulation and Model "
                    "Exchange): inspect an FMU, simulate it with FMPy's options, run, describe, "
                    "sweep or export a system description or an SSP.",
    )
    parser.add_argument("--version", action="version", version=f"syssimx {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for command in COMMANDS:
        command_parser = command.add_command(commands)
        command_parser.set_defaults(command_parser=command_parser)
    return parser
