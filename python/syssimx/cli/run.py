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
from .common import (
    CommandError,
    choose,
    is_ssp,
    warnings_as_lines,
    working_directory_importable,
)
from .options import add_output_file, add_run_limits, add_time_options
from .result_file import finished_despite_ctrl_c, write_bar


def add_command(commands: Any) -> argparse.ArgumentParser:
    run = commands.add_parser("run", help="build, initialize and run a system description")
    run.add_argument("config", help="a YAML or JSON system description, an SSP (.ssp "
                     "archive or .ssd file) or an OSP system structure (.xml)")
    add_time_options(run, "the description's run entry; for an SSP or OSP file its experiment")
    add_output_file(run, "write the results to this CSV file (long: component, port, time, "
                         "micro, value, unit)")
    run.add_argument("--wide", action="store_true",
                     help="write the CSV file wide, as FMPy and 'syssimx simulate -o' do: time, "
                          "then a column per Component.port (an event instant twice)")
    add_run_limits(run)
    run.add_argument("--algorithm", choices=ALGORITHM_NAMES, default=None,
                     help="the master algorithm (default: the description's; for an SSP "
                          "gauss_seidel)")
    run.add_argument("--input-order", type=int, default=None, choices=(0, 1, 2),
                     help="hold inputs over a step (0) or pass their first (1) or second (2) "
                          "derivatives to FMUs that interpolate inputs")
    run.add_argument("--extrapolate-held-inputs", action="store_true", default=None,
                     help="with --input-order 1 or 2, set the held inputs of FMUs that cannot "
                          "interpolate to their extrapolation's mean over the step")
    run.add_argument("--step-tolerance", type=float, default=None, metavar="TOL",
                     help="choose the communication steps by the coupling error, with rtol = "
                          "atol = TOL (rollback); the grid dt stays the output grid")
    run.add_argument("--threads", type=int, default=None, metavar="N",
                     help="step the FMU components on N threads (default: the description's, "
                          "else 1)")
    run.add_argument("--quiet", action="store_true",
                     help="no progress bar (there is none either when not on a terminal)")
    run.add_argument("--strict", action="store_true",
                     help="SSP/OSP: refuse what the file names that does not exist or that "
                          "syssimx does not support (default: one warning each, left out)")
    add_allow_module_option(run)
    run.set_defaults(run=run_config)
    return run


def run_config(args: argparse.Namespace, out: TextIO) -> None:
    from ..errors import SimulationTimeoutError
    from ..system.results import SimulationResult

    bar = not args.quiet and sys.stdout.isatty() and sys.stderr.isatty()
    options: dict[str, Any] = {"progress": True} if bar else {}
    options.update({k: v for k, v in (("timeout", args.timeout),
                                      ("output_interval", args.output_interval))
                    if v is not None})
    system, (t0, tf, dt) = _prepare_ssp(args) if is_ssp(args.config) else _prepare_config(args)
    system.initialize(t0)
    try:
        result, interrupted = run_keeping_partial(lambda: system.run(t0, tf, dt, **options))
    except SimulationTimeoutError as error:  # what was recorded is written first
        if args.output is None:
            raise
        recorded = SimulationResult.from_system(system, t0, tf, dt)
        written = _write_results(recorded, args, bar)
        raise CommandError(f"{error} (--timeout {args.timeout:g} s); the samples up to there "
                           f"are written to {written}") from error
    verb = "Completed" if interrupted is None else "Interrupted (what was finished)"
    out.write(f"{verb} '{result.system_name}': t in [{result.t0}, {result.tf}] s, "
              f"dt = {result.dt} s, algorithm = {result.algorithm}, "
              f"wall time = {result.wall_time:.3f} s\n")
    if len(result.events):
        out.write(_event_summary(result.events) + "\n")
    termination = result.termination
    if termination is not None:  # a component asked to stop: the end of the run, not a failure
        out.write(f"{termination}\n")
    if args.output is not None:
        with finished_despite_ctrl_c(str(args.output)):
            _write_results(result, args, bar)
            out.write(f"Results written to {args.output}\n")
    if interrupted is not None:
        raise interrupted


def _write_results(result: Any, args: argparse.Namespace, bar: bool) -> Path:
    """The result as --output asks (long, or --wide), a bar on a terminal if it takes long."""
    samples = len(result.micro)
    ports = sum(len(p) for _, p in result.histories.values())
    progress = write_bar(str(args.output), samples if args.wide else samples * ports, bar)

    def write(path: Path) -> object:
        if progress is not None:
            progress.reset()
        report = None if progress is None else progress.update
        return _write_wide(path, result, report) if args.wide \
            else result.to_csv(path, progress=report)
    try:
        return write_or_fallback(args.output, write)
    finally:
        if progress is not None:
            progress.close()


def _write_wide(path: Path, result: Any, progress: Any) -> Path:
    """FMPy's CSV of every component: time, then Component.port columns (the components
    share the samples' times)."""
    import numpy as np

    from ..system.csv_export import write_wide

    histories = result.histories
    t = next(iter(histories.values()))[0] if histories else np.empty(0)
    columns = {f"{component}.{port}": values
               for component, (_, ports) in histories.items() for port, values in ports.items()}
    return write_wide(path, t, columns, progress=progress)


def _prepare_config(args: argparse.Namespace) -> tuple[Any, tuple[float, float, float]]:
    """A system description's system and its times: the run entry, each replaced by an
    option given."""
    from ..system.config_source import Source, read_file
    from ..system.loader import build_system, run_settings

    with working_directory_importable():
        settings = run_settings(Source(Path(args.config)), read_file(args.config),
                                {"t0": args.start_time, "tf": args.stop_time,
                                 "dt": args.step_size})
        system = build_system(args.config, allowed_modules=args.allowed_modules)
        _choose_algorithm(system, args)
    return system, (settings["t0"], settings["tf"], settings["dt"])


EVENTS_LISTED = 5


def _event_summary(events: Any) -> str:
    """"Events: 3 (first at t = 0.465 P.wall_hit, ...)": the count and the first few."""
    shown = ", ".join(f"t = {e.t:.10g} {e.component}.{e.event}"
                      for e in events[:EVENTS_LISTED])
    more = ", ..." if len(events) > EVENTS_LISTED else ""
    first = "at" if len(events) == 1 else f"first {min(len(events), EVENTS_LISTED)} at"
    return f"Events: {len(events)} ({first} {shown}{more})"


def _algorithm_options_given(args: argparse.Namespace) -> bool:
    return any(getattr(args, name) is not None
               for name in ("algorithm", "threads", "input_order", "extrapolate_held_inputs",
                            "step_tolerance"))


def _choose_algorithm(system: Any, args: argparse.Namespace) -> None:
    """--algorithm replaces the description's algorithm; --threads, --input-order,
    --extrapolate-held-inputs and --step-tolerance set its coupling's."""
    if not _algorithm_options_given(args):
        return
    algorithm = algorithm_class(args.algorithm)() if args.algorithm is not None \
        else system.algorithm
    coupling = getattr(algorithm, "coupling", algorithm)  # a hybrid algorithm's coupling
    if args.threads is not None:
        coupling.threads = args.threads
    if args.input_order is not None:
        coupling.input_order = args.input_order
    if args.extrapolate_held_inputs is not None:
        coupling.extrapolate_held_inputs = args.extrapolate_held_inputs
    if args.step_tolerance is not None:
        from ..system.algorithms import StepControl

        coupling.step_control = StepControl(rtol=args.step_tolerance, atol=args.step_tolerance)
    system.set_algorithm(algorithm)


def _prepare_ssp(args: argparse.Namespace) -> tuple[Any, tuple[float, float, float]]:
    """A system file's system (SSP or OSP) and its times: over its default experiment (start 0
    when it has none); the stop time and the step come from the options, the file, else the
    step is FMPy's output interval for the run's length."""
    from ..system_files import read_system_file

    with warnings_as_lines():
        imported = read_system_file(args.config, strict=args.strict)
    experiment = imported.experiment
    t0 = choose(args.start_time, experiment.start_time, 0.0)
    tf = args.stop_time if args.stop_time is not None else experiment.stop_time
    if tf is None:
        raise CommandError(f"{args.config}: give --stop-time: the file has no stop time")
    dt = args.step_size if args.step_size is not None else experiment.step_size
    if dt is None:
        from fmpy.util import auto_interval

        dt = float(auto_interval(float(tf) - t0))
    _choose_algorithm(imported.system, args)
    return imported.system, (t0, float(tf), float(dt))
