"""`syssimx simulate`: one FMU run as a one-component system, as FMPy's `simulate` does."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Any, TextIO

from ..atomic_file import write_or_fallback
from ..core.literal import literal
from ..core.port import PortType
from ..core.suggest import did_you_mean
from ..fmu.info import INTERFACES
from ..partial_results import run_keeping_partial
from ..system.csv_export import write_wide
from .common import CommandError, choose, resolve_fmu
from .options import add_output_file, add_run_limits, add_time_options
from .result_file import finished_despite_ctrl_c, write_bar
from .simulate_input import communication_points, connect_input, run_through

# FMPy's interface names, and ours
INTERFACE_NAMES = {"auto": "auto", "CoSimulation": "co-simulation",
                   "ModelExchange": "model-exchange", **{i: i for i in INTERFACES}}
DIRECTIONS = {"-1": -1, "falling": -1, "0": 0, "both": 0, "1": 1, "+1": 1, "rising": 1}


def add_command(commands: Any) -> argparse.ArgumentParser:
    simulate = commands.add_parser("simulate", help="simulate one FMU as a one-component system")
    simulate.add_argument("fmu", help="path to a .fmu file, or the name of a bundled FMU")
    add_time_options(simulate, "the FMU's default experiment, else start 0, stop start + 1, "
                     "and FMPy's step: the default experiment's step doubled while there are "
                     "over 1000 steps, else 500 to 1000 round steps")
    simulate.add_argument("--relative-tolerance", "--tolerance", type=float, default=None,
                          dest="tolerance", metavar="RTOL",
                          help="relative tolerance passed to the FMU (default: the FMU's "
                               "default experiment)")
    simulate.add_argument("--fmi-type", "--interface-type", "--interface", default="auto",
                          type=_interface, dest="interface", metavar="TYPE",
                          help="the FMU interface to run: CoSimulation (fmi2DoStep), or "
                          "ModelExchange integrated by syssimx with CVODE (also co-simulation, "
                          "model-exchange; default auto: Co-Simulation when the FMU has it, "
                          "else Model Exchange)")
    simulate.add_argument("--input-file", "--input", type=Path, default=None, dest="input",
                          metavar="CSV",
                          help="input signals, a CSV file in FMPy's format (a time column, "
                               "then one column per input, matched by name)")
    simulate.add_argument("--start-values", nargs="+", default=[], metavar="NAME VALUE",
                          help="start values of parameters or constant inputs, as name-value "
                               "pairs (FMPy's form)")
    simulate.add_argument("--set", action="append", default=[], type=_assignment,
                          metavar="NAME=VALUE", dest="assignments",
                          help="set a parameter, or hold an input at a constant value "
                               "(repeatable)")
    simulate.add_argument("--event", action="append", default=[], type=_event,
                          metavar="VAR:DIRECTION", dest="events",
                          help="locate zero crossings of output VAR; DIRECTION is -1|falling, "
                               "1|rising or 0|both (repeatable)")
    add_output_file(simulate, "write the outputs over time to this CSV file in FMPy's format "
                              "(time, then one column per output)")
    simulate.add_argument("--output-variables", nargs="+", default=None, metavar="NAME",
                          help="the outputs to write and print (default: every output)")
    simulate.add_argument("--units", action="store_true",
                          help="head the CSV columns 'name [unit]' (FMPy's reader then keeps "
                               "the unit in the name)")
    add_run_limits(simulate, " (given alone, it is also the step, as in FMPy)")
    simulate.add_argument("--plot", type=Path, default=None, metavar="FILE",
                          help="plot the real outputs to this image (.png, .svg, .pdf, ...)")
    simulate.set_defaults(run=run_simulate)
    return simulate


def _assignment(text: str) -> tuple[str, bool | int | float | str]:
    name, equals, value = text.partition("=")
    if not equals or not name.strip():
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    return name.strip(), literal(value.strip())


def _interface(text: str) -> str:
    if text not in INTERFACE_NAMES:
        raise argparse.ArgumentTypeError(f"expected one of {', '.join(INTERFACE_NAMES)}; "
                                         f"got {text!r}")
    return INTERFACE_NAMES[text]


def _start_values(pairs: list[str]) -> list[tuple[str, bool | int | float | str]]:
    """--start-values NAME VALUE ...: FMPy's name-value pairs."""
    if len(pairs) % 2:
        raise CommandError(f"--start-values takes name-value pairs; got {len(pairs)} words "
                           f"({' '.join(pairs)})")
    return [(name, literal(value)) for name, value in zip(pairs[::2], pairs[1::2], strict=True)]


def _event(text: str) -> tuple[str, int]:
    variable, colon, direction = text.rpartition(":")
    if not colon or not variable or direction.lower() not in DIRECTIONS:
        raise argparse.ArgumentTypeError(
            f"expected VAR:DIRECTION with DIRECTION one of -1, 0, 1, falling, both, rising; "
            f"got {text!r}"
        )
    return variable, DIRECTIONS[direction.lower()]


def run_simulate(args: argparse.Namespace, out: TextIO) -> None:
    from .. import FMUComponent, JacobiAlgorithm, SimulationResult, System
    from ..errors import SimulationTimeoutError
    from ..fmu.info import read_fmu

    path = resolve_fmu(args.fmu)
    md = read_fmu(path).description  # what the component reads too: read once, by syssimx
    t0, tf, dt = _experiment(args, md.defaultExperiment,
                             getattr(md.coSimulation, "fixedInternalStepSize", None))
    options = {} if args.tolerance is None else {"tolerance": args.tolerance}
    component = FMUComponent(md.modelName or path.stem, str(path), interface=args.interface,
                             **options)
    assignments = dict([*_start_values(args.start_values), *args.assignments])
    held_inputs = {n: v for n, v in assignments.items() if n in component.input_specs}
    component.set_parameters(**{n: v for n, v in assignments.items() if n not in held_inputs})
    if held_inputs:
        component.set_inputs(held_inputs)
    for variable, direction in args.events:
        if variable not in component.output_specs:
            raise CommandError(f"--event {variable}: not an output of {path.name}"
                               f"{did_you_mean(variable, component.output_specs)}; outputs: "
                               f"{', '.join(component.output_specs)}")
        component.add_event_indicator(_event_name(variable), variable=variable,
                                      direction=direction)
    written = _written_outputs(component, args.output_variables, path.name)
    system = System(name=f"syssimx simulate {path.name}")
    system.add_component(component)
    events: list[float] = []
    if args.input is not None:
        source = connect_input(system, component, args.input)
        # FMPy sets the inputs at the start of each step: the Jacobi coupling's timing
        system.set_algorithm(JacobiAlgorithm())
        # the engine integrates a Model Exchange FMU: any step is fine
        if source is not None and (component.model_exchange or
                                   md.coSimulation.canHandleVariableCommunicationStepSize):
            events = source.event_times().tolist()
    system.initialize(t0)
    limits = {"timeout": args.timeout}
    if args.output_interval is not None and not events:
        limits["output_interval"] = args.output_interval
    timed_out = None
    try:
        result, interrupted = run_keeping_partial(
            lambda: run_through(system, communication_points(t0, tf, dt, events), dt,
                                args.timeout) if events else system.run(t0, tf, dt, **limits))
    except SimulationTimeoutError as error:  # the samples up to there are written first
        timed_out, interrupted = error, None
        result = SimulationResult.from_system(system, t0, tf, dt)

    t, values = result[component.name]
    columns = {name: values[name] for name in written if name in values}
    if args.output is not None:
        units = result.units[component.name] if args.units else {}
        with finished_despite_ctrl_c(str(args.output)):
            progress = write_bar(str(args.output), len(t),
                                 sys.stdout.isatty() and sys.stderr.isatty())
            try:
                write_or_fallback(args.output, lambda path: write_wide(
                    path, t, columns, units, None if progress is None else progress.update))
            finally:
                if progress is not None:
                    progress.close()
            out.write(f"wrote {len(t)} samples of {len(columns)} outputs to {args.output}\n")
    if timed_out is not None:
        raise CommandError(f"{timed_out} (--timeout {args.timeout:g} s)")
    if args.plot is not None:
        from ..viz.plot import plot_result

        signals = [f"{component.name}.{name}" for name in written
                   if component.output_specs[name].type == PortType.REAL]
        plot_result(result, signals, path=args.plot)
        out.write(f"wrote the plot to {args.plot}\n")
    for record in getattr(result, "events", None) or []:
        out.write(f"event {record.component}.{record.name} at t = {record.t!r}\n")
    termination = result.termination
    if termination is not None:  # a component asked to stop: the end of the run, not a failure
        reason = f": {termination.message}" if termination.message else ""
        out.write(f"{termination.component} terminated the run at t = {termination.time!r}"
                  f"{reason}\n")
    if args.output is None:
        for name, series in columns.items():
            out.write(f"{name} = {series[-1]:.12g} at t = {t[-1]:.12g}\n")
    if interrupted is not None:
        raise interrupted


def _written_outputs(component: Any, chosen: list[str] | None, fmu_name: str) -> list[str]:
    """The outputs --output-variables names (every output without it), event outputs aside."""
    outputs = [name for name, spec in component.output_specs.items()
               if spec.type != PortType.EVENT]
    if chosen is None:
        return outputs
    for name in chosen:
        if name not in outputs:
            raise CommandError(f"--output-variables {name}: not an output of {fmu_name}"
                               f"{did_you_mean(name, outputs)}; outputs: {', '.join(outputs)}")
    return list(dict.fromkeys(chosen))


def _experiment(args: argparse.Namespace, experiment: Any, fixed_step: str | None = None
                ) -> tuple[float, float, float]:
    """Start, stop and step: given, else from the default experiment, else FMPy's defaults.
    FMPy steps an FMI 3.0 FMU with a fixedInternalStepSize by that step first."""
    t0 = choose(args.start_time, getattr(experiment, "startTime", None), 0.0)
    tf = choose(args.stop_time, getattr(experiment, "stopTime", None), t0 + 1.0)
    if not tf > t0:
        raise CommandError(f"need stop time > start time; got start {t0}, stop {tf}")
    if args.step_size is not None or args.output_interval is not None:
        # FMPy communicates at the output interval; a step given too is the step
        dt = float(args.step_size if args.step_size is not None else args.output_interval)
    elif fixed_step is not None or getattr(experiment, "stepSize", None) is not None:
        dt = float(fixed_step if fixed_step is not None else experiment.stepSize)
        while dt > 0 and (tf - t0) / dt > 1000:  # FMPy's output interval for a long experiment
            dt *= 2
        dt = min(dt, tf - t0)  # FMPy makes one step of a run shorter than the experiment's
    else:
        from fmpy.util import auto_interval

        dt = float(auto_interval(tf - t0))
    if not dt > 0:
        raise CommandError(f"need step size > 0; got {dt}")
    _check_run_length(t0, tf, dt)
    return t0, tf, dt


def _check_run_length(t0: float, tf: float, dt: float) -> None:
    """Finite times and at most the engine's number of steps, refused here before anything
    is built: an infinite or astronomic stop time would otherwise walk (or, FMPy's way, list)
    its communication points without end."""
    from ..system.system import MAX_GRID_STEPS

    for label, value in (("--start-time", t0), ("--stop-time", tf), ("--step-size", dt)):
        if not math.isfinite(value):
            raise CommandError(f"{label} must be a finite number of seconds; got {value}")
    steps = (tf - t0) / dt
    if steps > MAX_GRID_STEPS:
        raise CommandError(f"the run from {t0:g} s to {tf:g} s in steps of {dt:g} s takes "
                           f"{steps:.3g} steps; syssimx runs at most {MAX_GRID_STEPS:.0e} "
                           "steps: give a smaller --stop-time or a larger --step-size")


def _event_name(variable: str) -> str:
    return f"{variable}_crossing"
