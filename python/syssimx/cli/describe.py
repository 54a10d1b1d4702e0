"""`syssimx describe`: the structure of a system description or SSP."""

from __future__ import annotations

import argparse
from typing import Any, TextIO

from ..system.component_classes import add_allow_module_option
from .common import choose, is_ssp, warnings_as_lines, working_directory_importable


def add_command(commands: Any) -> argparse.ArgumentParser:
    describe = commands.add_parser("describe", help="print the structure of a system "
                                   "description: components, connections, order, loops")
    describe.add_argument("config", help="a YAML or JSON system description, an SSP "
                          "(.ssp archive or .ssd file) or an OSP system structure (.xml)")
    describe.add_argument("--initialize", action="store_true",
                          help="initialize the system first (at run.t0, else 0)")
    describe.add_argument("--strict", action="store_true",
                          help="SSP/OSP: refuse what run --strict refuses")
    add_allow_module_option(describe)
    describe.set_defaults(run=run_describe)
    return describe


def run_describe(args: argparse.Namespace, out: TextIO) -> None:
    from ..system.loader import build_system, load_config

    if is_ssp(args.config):
        from ..system_files import read_system_file

        with warnings_as_lines():
            imported = read_system_file(args.config, strict=args.strict)
        if args.initialize:
            imported.system.initialize(choose(None, imported.experiment.start_time, 0.0))
        out.write(imported.system.describe() + "\n")
        return
    with working_directory_importable():
        system = build_system(args.config, allowed_modules=args.allowed_modules)
    if args.initialize:
        run = load_config(args.config).get("run") or {}
        system.initialize(float(run.get("t0", 0.0)) if isinstance(run, dict) else 0.0)
    out.write(system.describe() + "\n")
