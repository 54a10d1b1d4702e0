"""`syssimx simulate`: one FMU run as a one-component system, as FMPy's `simulate` does."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any, TextIO

from ..atomic_file import write_or_fallback
from ..core.literal import literal
from ..fmu.info import INTERFACES
from ..partial_results import run_keeping_partial
from ..system.csv_export import write_wide
from .common import CommandError, choose, resolve_fmu
from .simulate_input import communication_points, connect_input, run_through

DIRECTIONS = {"-1": -1, "falling": -1, "0": 0, "both": 0, "1": 1, "+1": 1, "rising": 1}


def add_command(commands: Any) -> None:
    simulate = commands.add_parser("simulate", help="simulate one FMU as a one-component system")
    simulate.add_argument("fmu", help="path to a .fmu file, or the name of a bundled FMU")
    simulate.add_argument("--start-time", type=float, default=None, metavar="T0",
                          help="start time in s (default: the FMU's default experiment, or 0)")
    simulate.add_argument("--stop-time", type=float, default=None, metavar="TF",
                          help="stop time in s (default: the FMU's default experiment, or 1)")
    simulate.add_argument("--step-size", type=float, default=None, metavar="DT",
                          help="communication step in s (default: FMPy's: the FMU's default "
                               "experiment step, doubled while there are over 1000 steps, else "
                               "500 to 1000 round steps)")
    simulate.add_argument("--tolerance", type=float, default=None, metavar="RTOL",
                          help="relative tolerance passed to the FMU (default: the FMU's "
                               "default experiment)")
    simulate.add_argument("--interface", choices=("auto", *INTERFACES), default="auto",
                          help="the FMU interface to run: Co-Simulation (fmi2DoStep), or Model "
                          "Exchange integrated by syssimx with CVODE (default auto: "
                          "Co-Simulation when the FMU has it, else Model Exchange)")
    simulate.add_argument("--input", type=Path, default=None, metavar="CSV",
                          help="input signals, a CSV file in FMPy's format (a time column, "
                               "then one column per input, matched by name)")
    simulate.add_argument("--set", action="append", default=[], type=_assignment,
                          metavar="NAME=VALUE", dest="assignments",
                          help="set a parameter, or hold an input at a constant value "
                               "(repeatable)")
    simulate.add_argument("--event", action="append", default=[], type=_event,
                          metavar="VAR:DIRECTION", dest="events",
                          help="locate zero crossings of output VAR; DIRECTION is -1|falling, "
                               "1|rising or 0|both (repeatable)")
    simulate.add_argument("--output", "-o", type=Path, default=None, metavar="CSV",
                          help="write the outputs over time to this CSV file")
    simulate.add_argument("--plot", type=Path, default=None, metavar="PNG",
                          help="plot the real outputs to this PNG file")
    simulate.set_defaults(run=run_simulate)


def _assignment(text: str) -> tuple[str, bool | int | float | str]:
    name, equals, value = text.partition("=")
    if not equals or not name.strip():
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    return name.strip(), literal(value.strip())


def _event(text: str) -> tuple[str, int]:
    variable, colon, direction = text.rpartition(":")
    if not colon or not variable or direction.lower() not in DIRECTIONS:
        raise argparse.ArgumentTypeError(
            f"expected VAR:DIRECTION with DIRECTION one of -1, 0, 1, falling, both, rising; "
            f"got {text!r}"
        )
    return variable, DIRECTIONS[direction.lower()]


def run_simulate(args: argparse.Namespace, out: TextIO) -> None:
    from .. import FMUComponent, JacobiAlgorithm, System
    from ..fmu.info import read_fmu

    path = resolve_fmu(args.fmu)
    md = read_fmu(path).description  # what the component reads too: read once, by syssimx
    t0, tf, dt = _experiment(args, md.defaultExperiment,
                             getattr(md.coSimulation, "fixedInternalStepSize", None))
    options = {} if args.tolerance is None else {"tolerance": args.tolerance}
    component = FMUComponent(md.modelName or path.stem, str(path), interface=args.interface,
                             **options)
    assignments = dict(args.assignments)
    held_inputs = {n: v for n, v in assignments.items() if n in component.input_specs}
    component.set_parameters(**{n: v for n, v in assignments.items() if n not in held_inputs})
    if held_inputs:
        component.set_inputs(held_inputs)
    for variable, direction in args.events:
        if variable not in component.output_specs:
            raise CommandError(f"--event {variable}: not an output of {path.name}; outputs: "
                               f"{', '.join(component.output_specs)}")
        component.add_event_indicator(_event_name(variable), variable=variable,
                                      direction=direction)
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
    result, interrupted = run_keeping_partial(
        lambda: run_through(system, communication_points(t0, tf, dt, events), dt) if events
        else system.run(t0, tf, dt))

    t, values = result[component.name]
    columns = {name: values[name] for name, spec in component.output_specs.items()
               if name in values and str(getattr(spec.type, "value", spec.type)) != "event"}
    if args.output is not None:
        write_or_fallback(args.output, lambda path: write_wide(path, t, columns,
                                                               result.units[component.name]))
        out.write(f"wrote {len(t)} samples of {len(columns)} outputs to {args.output}\n")
    if args.plot is not None:
        from ..viz.plot import plot_result

        signals = [f"{component.name}.{name}" for name, spec in component.output_specs.items()
                   if name in columns and str(getattr(spec.type, "value", spec.type)) == "real"]
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


def _experiment(args: argparse.Namespace, experiment: Any, fixed_step: str | None = None
                ) -> tuple[float, float, float]:
    """Start, stop and step: given, else from the default experiment, else FMPy's defaults.
    FMPy steps an FMI 3.0 FMU with a fixedInternalStepSize by that step first."""
    t0 = choose(args.start_time, getattr(experiment, "startTime", None), 0.0)
    tf = choose(args.stop_time, getattr(experiment, "stopTime", None), t0 + 1.0)
    if not tf > t0:
        raise CommandError(f"need stop time > start time; got start {t0}, stop {tf}")
    if args.step_size is not None:
        dt = float(args.step_size)
    elif fixed_step is not None or getattr(experiment, "stepSize", None) is not None:
        dt = float(fixed_step if fixed_step is not None else experiment.stepSize)
        while dt > 0 and (tf - t0) / dt > 1000:  # FMPy's output interval for a long experiment
            dt *= 2
    else:
        from fmpy.util import auto_interval

        dt = float(auto_interval(tf - t0))
    if not dt > 0:
        raise CommandError(f"need step size > 0; got {dt}")
    return t0, tf, dt


def _event_name(variable: str) -> str:
    return f"{variable}_crossing"
