"""`syssimx export`: a system description, SSP or OSP file as one Co-Simulation FMU."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any, TextIO

from ..output_check import check_output
from ..system.component_classes import add_allow_module_option
from .common import is_ssp, warnings_as_lines, working_directory_importable


def add_command(commands: Any) -> argparse.ArgumentParser:
    export = commands.add_parser(
        "export", help="export a system as one Co-Simulation FMU (FMI 2.0 or 3.0) whose "
        "binary is the engine: its events are located inside doStep")
    export.add_argument("config", help="a YAML or JSON system description, an SSP (.ssp "
                        "archive or .ssd file) or an OSP system structure (.xml)")
    export.add_argument("-o", "--fmu", type=Path, required=True, dest="fmu_file",
                        metavar="OUT.fmu", help="the FMU to write")
    export.add_argument("--fmi-version", choices=("2.0", "3.0"), default="2.0",
                        help="the FMI version of the FMU (default: 2.0)")
    export.add_argument("--input", action="append", default=None, dest="inputs",
                        metavar="C.PORT", help="an input of the FMU (repeatable; default: "
                        "every Real member input no connection drives)")
    export.add_argument("--output", action="append", default=None, dest="outputs",
                        metavar="C.PORT", help="an output of the FMU (repeatable; default: "
                        "every Real member output)")
    export.add_argument("--parameter", action="append", default=[], dest="parameters",
                        metavar="C.NAME", help="a member's Real parameter the FMU lets an "
                        "importer set before initialization (repeatable; default: none)")
    export.add_argument("--step-size", "--dt", type=float, default=None, dest="step_size",
                        metavar="DT", help="the system's communication step inside each doStep "
                        "(default: the file's run dt or experiment step; none: the importer's)")
    export.add_argument("--strict", action="store_true",
                        help="SSP/OSP: refuse what run --strict refuses")
    add_allow_module_option(export)
    export.set_defaults(run=run_export)
    return export


def run_export(args: argparse.Namespace, out: TextIO) -> None:
    check_output(args.fmu_file, "FMU", (".fmu",))
    system, (start, stop, step) = _system_file(args) if is_ssp(args.config) \
        else _description(args)
    step = args.step_size if args.step_size is not None else step
    written = system.export_fmu(args.fmu_file, fmi_version=args.fmi_version,
                                inputs=args.inputs, outputs=args.outputs,
                                parameters=args.parameters, step_size=step,
                                start_time=start, stop_time=stop)
    out.write(f"Exported '{system.name}' as FMI {args.fmi_version} Co-Simulation FMU "
              f"{written}\n")


Times = tuple[float | None, float | None, float | None]


def _system_file(args: argparse.Namespace) -> tuple[Any, Times]:
    from ..system_files import read_system_file

    with warnings_as_lines():
        # the FMU carries no host process: an OSP file's proxy FMUs run in its process
        imported = read_system_file(args.config, strict=args.strict, proxies_in_process=True)
    experiment = imported.experiment
    return imported.system, (experiment.start_time, experiment.stop_time, experiment.step_size)


def _description(args: argparse.Namespace) -> tuple[Any, Times]:
    from ..system.loader import build_system, load_config

    with working_directory_importable():
        system = build_system(args.config, allowed_modules=args.allowed_modules)
    run = load_config(args.config).get("run")
    settings = run if isinstance(run, dict) else {}

    def time(key: str) -> float | None:
        value = settings.get(key)
        return float(value) if isinstance(value, int | float) else None
    return system, (time("t0"), time("tf"), time("dt"))
