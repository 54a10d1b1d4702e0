"""`syssimx fmus`: the FMUs bundled with syssimx and where they are."""

from __future__ import annotations

import argparse
from typing import Any, TextIO

from .. import fmus
from .common import CommandError


def add_command(commands: Any) -> argparse.ArgumentParser:
    listing = commands.add_parser("fmus", help="list the FMUs bundled with syssimx")
    listing.set_defaults(run=run_fmu_list)
    return listing


def run_fmu_list(args: argparse.Namespace, out: TextIO) -> None:
    names = fmus.available()
    if not names:
        raise CommandError("no bundled FMUs found (is syssimx built and installed?)")
    width = max(len(name) for name in names)
    for name in names:
        out.write(f"{name.ljust(width)}  {fmus.path(name)}\n")
