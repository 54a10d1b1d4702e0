"""Options several commands share, under one set of names: FMPy's (`--start-time`,
`--stop-time`, `--step-size`, `--output-file`, ...), with SysSimX's short names (`--t0`,
`--tf`, `--dt`, `--output`/`-o`) as aliases."""

from __future__ import annotations

import argparse
from pathlib import Path


def add_time_options(parser: argparse.ArgumentParser, default: str) -> None:
    """--start-time/--t0, --stop-time/--tf, --step-size/--dt; `default` says where a value
    left out comes from."""
    parser.add_argument("--start-time", "--t0", type=float, default=None, dest="start_time",
                        metavar="T0", help=f"start time in s (default: {default})")
    parser.add_argument("--stop-time", "--tf", type=float, default=None, dest="stop_time",
                        metavar="TF", help=f"stop time in s (default: {default})")
    parser.add_argument("--step-size", "--dt", type=float, default=None, dest="step_size",
                        metavar="DT", help=f"communication (macro) step in s (default: {default})")


def add_output_file(parser: argparse.ArgumentParser, what: str) -> None:
    """--output-file (FMPy's), also --output and -o."""
    parser.add_argument("--output-file", "--output", "-o", type=Path, default=None,
                        dest="output", metavar="FILE", help=what)


def add_run_limits(parser: argparse.ArgumentParser, interval_note: str = "") -> None:
    """FMPy's --output-interval and --timeout."""
    parser.add_argument("--output-interval", type=float, default=None, metavar="S",
                        help="record every S seconds of simulated time, a whole multiple of "
                             f"the step{interval_note}")
    parser.add_argument("--timeout", type=float, default=None, metavar="S",
                        help="stop the run after S seconds of wall time; the samples up to "
                             "there are written, and the command fails")
