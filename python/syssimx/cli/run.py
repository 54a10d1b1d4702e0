"""`syssimx run`: build, initialize and run a system description or SSP."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any, TextIO

from ..atomic_file import write_or_fallback
from ..partial_results import run_keeping_partial
from ..system.algorithm_table import ALGORITHM_NAMES, algorithm_class
from ..system.component_classes import add_allow_module_option
from .common import CommandError, choose, is_ssp, working_directory_importable


def add_command(commands: Any) -> None:
    run = commands.add_parser("run", help="build, initialize and run a system description")
    run.add_argument("config", help="a YAML or JSON system description, or an SSP (.ssp "
                     "archive or .ssd file)")
    run.add_argument("--t0", type=float, default=None, help="start time in s (default: the "
                     "description's run.t0)")
    run.add_argument("--tf", type=float, default=None, help="end time in s (default: run.tf)")
    run.add_argument("--dt", type=float, default=None, help="macro step in s (default: run.dt)")
    run.add_argument("--output", "-o", type=Path, default=None, metavar="CSV",
                     help="write the results to this CSV file (long: component, port, time, "
                          "value, unit)")
    run.add_argument("--algorithm", choices=ALGORITHM_NAMES, default=None,
                     help="the master algorithm (default: the description's; for an SSP "
                          "gauss_seidel)")
    run.add_argument("--input-order", type=int, default=None, choices=(0, 1, 2),
                     help="hold inputs over a step (0) or pass their first (1) or second (2) "
                          "derivatives to FMUs that interpolate inputs")
    run.add_argument("--step-tolerance", type=float, default=None, metavar="TOL",
                     help="choose the communication steps by the coupling error, with rtol = "
                          "atol = TOL (rollback); the grid dt stays the output grid")
    run.add_argument("--threads", type=int, default=None, metavar="N",
                     help="step the FMU components on N threads (default: the description's, "
                          "else 1)")
    run.add_argument("--quiet", action="store_true",
                     help="no progress bar (there is none either when not on a terminal)")
    add_allow_module_option(run)
    run.set_defaults(run=run_config)


def run_config(args: argparse.Namespace, out: TextIO) -> None:
    result, interrupted = run_keeping_partial(lambda: _config_result(args))
    verb = "Completed" if interrupted is None else "Interrupted (what was finished)"
    out.write(f"{verb} '{result.system_name}': t in [{result.t0}, {result.tf}] s, "
              f"dt = {result.dt} s, algorithm = {result.algorithm}, "
              f"wall time = {result.wall_time:.3f} s\n")
    termination = result.termination
    if termination is not None:  # a component asked to stop: the end of the run, not a failure
        out.write(f"{termination}\n")
    if args.output is not None:
        write_or_fallback(args.output, result.to_csv)
        out.write(f"Results written to {args.output}\n")
    if interrupted is not None:
        raise interrupted


def _config_result(args: argparse.Namespace) -> Any:
    bar = not args.quiet and sys.stdout.isatty() and sys.stderr.isatty()
    options = {"progress": True} if bar else {}
    if is_ssp(args.config):
        result = _run_ssp(args, options)
    else:
        from ..system.config_source import Source, read_file
        from ..system.loader import build_system, run_from_config, run_settings

        with working_directory_importable():
            if not _algorithm_options_given(args):
                result = run_from_config(args.config, t0=args.t0, tf=args.tf, dt=args.dt,
                                         progress=options.get("progress"),
                                         allowed_modules=args.allowed_modules)
            else:
                settings = run_settings(Source(Path(args.config)), read_file(args.config),
                                        {"t0": args.t0, "tf": args.tf, "dt": args.dt})
                system = build_system(args.config, allowed_modules=args.allowed_modules)
                _choose_algorithm(system, args)
                system.initialize(settings["t0"])
                result = system.run(settings["t0"], settings["tf"], settings["dt"], **options)
    return result


def _algorithm_options_given(args: argparse.Namespace) -> bool:
    return any(getattr(args, name) is not None
               for name in ("algorithm", "threads", "input_order", "step_tolerance"))


def _choose_algorithm(system: Any, args: argparse.Namespace) -> None:
    """--algorithm replaces the description's algorithm; --threads, --input-order and
    --step-tolerance set its coupling's."""
    if not _algorithm_options_given(args):
        return
    algorithm = algorithm_class(args.algorithm)() if args.algorithm is not None \
        else system.algorithm
    coupling = getattr(algorithm, "coupling", algorithm)  # a hybrid algorithm's coupling
    if args.threads is not None:
        coupling.threads = args.threads
    if args.input_order is not None:
        coupling.input_order = args.input_order
    if args.step_tolerance is not None:
        from ..system.algorithms import StepControl

        coupling.step_control = StepControl(rtol=args.step_tolerance, atol=args.step_tolerance)
    system.set_algorithm(algorithm)


def _run_ssp(args: argparse.Namespace, options: dict[str, Any]) -> Any:
    """An SSP's system over its default experiment (start 0 when it has none); the stop time
    and the step come from the experiment, the OSP fixed-step annotation, or the options."""
    from ..ssp import read

    imported = read(args.config)
    experiment = imported.experiment
    t0 = choose(args.t0, experiment.start_time, 0.0)
    tf = args.tf if args.tf is not None else experiment.stop_time
    dt = args.dt if args.dt is not None else experiment.step_size
    if tf is None or dt is None:
        missing = " and ".join(o for o, v in (("--tf", tf), ("--dt", dt)) if v is None)
        raise CommandError(f"{args.config}: give {missing}: the SSP has no "
                           + ("stop time in its DefaultExperiment" if tf is None else
                              "step size (an OSP FixedStepAlgorithm baseStepSize annotation)"))
    _choose_algorithm(imported.system, args)
    imported.system.initialize(t0)
    return imported.system.run(t0, float(tf), float(dt), **options)
