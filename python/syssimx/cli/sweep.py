"""`syssimx sweep`: a system run once per parameter set in worker processes (its work is done by
`syssimx.ensemble.command`)."""

from __future__ import annotations

import argparse
from typing import Any, TextIO

from ..system.component_classes import add_allow_module_option
from .options import add_output_file, add_time_options


def add_command(commands: Any) -> argparse.ArgumentParser:
    sweep = commands.add_parser("sweep", help="run a system once per parameter set, in "
                                "parallel worker processes (Dask)")
    sweep.add_argument("system", metavar="SYSTEM",
                       help="a system file (YAML/JSON), or MODULE:FUNCTION or "
                            "FILE.py:FUNCTION returning a System")
    sweep.add_argument("--param", action="append", required=True, type=_parameter_values,
                       metavar="C.P=VALUES", dest="parameters",
                       help="values of Component.parameter: START:STOP:COUNT, A,B,C or one "
                            "value (repeatable)")
    sweep.add_argument("--mode", choices=("grid", "zip"), default="grid",
                       help="every combination of the values (grid) or their i-th values "
                            "together (zip)")
    # the time options of `run`: a sweep runs the same system descriptions
    add_time_options(sweep, "the system file's run entry")
    where = sweep.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, default=None, metavar="N",
                       help="worker processes of the embedded cluster (default: one per core)")
    where.add_argument("--scheduler", default=None, metavar="ADDR",
                       help="run on the Dask cluster of this scheduler, e.g. tcp://host:8786")
    sweep.add_argument("--member-timeout", type=float, default=None, metavar="S",
                       help="fail a member whose run takes longer than S seconds")
    add_output_file(sweep, "write the results: .csv or .parquet (one row per member and "
                           "sample) or .nc (the xarray dataset)")
    sweep.add_argument("--quiet", action="store_true", dest="no_progress",
                       help="no progress bar")
    add_allow_module_option(sweep)
    sweep.set_defaults(run=run_sweep)
    return sweep


def _parameter_values(text: str) -> tuple[str, list[bool | int | float | str]]:
    from ..ensemble.command import parameter_values

    return parameter_values(text)


def run_sweep(args: argparse.Namespace, out: TextIO) -> None:
    from ..ensemble.command import run_sweep

    run_sweep(args, out)
