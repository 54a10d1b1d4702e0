"""The ``syssimx`` command line: inspect an FMU, list the bundled FMUs, simulate one FMU, run
or describe a system description (YAML or JSON) or an SSP (.ssp archive or .ssd file), sweep
a system over parameters.

    syssimx info pendulum_cvode
    syssimx fmus
    syssimx simulate pendulum_euler --stop-time 1 --step-size 0.05 --set theta0=0.5 \\
        --event theta:-1 --output results.csv --plot results.png
    syssimx simulate Feedthrough.fmu --input signals.csv --tolerance 1e-8
    syssimx run system.yaml --tf 10 --dt 0.01 -o results.csv
    syssimx describe system.yaml
    syssimx run system.ssp --algorithm jacobi
    syssimx sweep system.yaml --param P.theta0=0.1:0.5:50 --param P.L=0.5,0.6 -o out.nc
    syssimx --version

An FMU argument is a path to a .fmu file or the name of a bundled FMU. Bad usage exits with
code 2, a failure while running with code 1; both print one clear line on stderr.
"""

from __future__ import annotations

import argparse
import itertools
import math
import os
import sys
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any, TextIO

import numpy as np

from . import __version__, fmus
from .components.model_description import INTERFACES
from .core.literal import literal
from .core.port import PortType
from .graph.analysis import feedthrough_from_model_description
from .system.csv_export import write_wide

__all__ = ["build_parser", "main"]

if TYPE_CHECKING:
    from .components.table_source import TableSource

ALGORITHMS = ("jacobi", "gauss_seidel", "hybrid")
SSP_SUFFIXES = (".ssp", ".ssd")
DIRECTIONS = {"-1": -1, "falling": -1, "0": 0, "both": 0, "1": 1, "+1": 1, "rising": 1}
CAPABILITIES = (
    "canGetAndSetFMUstate",
    "canSerializeFMUstate",
    "canHandleVariableCommunicationStepSize",
    "providesDirectionalDerivative",
    "canInterpolateInputs",
    "needsExecutionTool",
)
# what an FMI 3.0 Co-Simulation FMU adds: whether it handles its own events at their time
CAPABILITIES_FMI3 = ("hasEventMode", "mightReturnEarlyFromDoStep",
                     "canReturnEarlyAfterIntermediateUpdate")


# the numpy type FMPy casts an input column to, by the input's type
_TABLE_DTYPES = {PortType.REAL: np.float64, PortType.INT: np.int32, PortType.BOOL: np.bool_}


class CommandError(Exception):
    """A failure the user can act on: printed as one line, exit code 1."""


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line with ``argv`` (default: sys.argv[1:]); returns the exit code."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exit_request:  # argparse has printed usage or help already
        return int(exit_request.code or 0)
    try:
        args.run(args, sys.stdout)
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


def build_parser() -> argparse.ArgumentParser:
    """The parser of the `syssimx` command line, with a subcommand per command (also what the
    documentation's command-line reference is generated from)."""
    parser = argparse.ArgumentParser(
        prog="syssimx",
        description="Hybrid co-simulation of FMI 2.0 Co-Simulation FMUs.",
    )
    parser.add_argument("--version", action="version", version=f"syssimx {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    info = commands.add_parser("info", help="describe an FMU: variables and capabilities")
    info.add_argument("fmu", help="path to a .fmu file, or the name of a bundled FMU")
    info.set_defaults(run=_info)

    listing = commands.add_parser("fmus", help="list the FMUs bundled with syssimx")
    listing.set_defaults(run=_list_fmus)

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
    simulate.set_defaults(run=_simulate)

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
    run.add_argument("--algorithm", choices=ALGORITHMS, default=None,
                     help="the master algorithm (default: the description's; for an SSP "
                          "gauss_seidel)")
    run.add_argument("--threads", type=int, default=None, metavar="N",
                     help="step the FMU components on N threads (default: the description's, "
                          "else 1)")
    run.add_argument("--quiet", action="store_true",
                     help="no progress bar (there is none either when not on a terminal)")
    run.set_defaults(run=_run_config)

    describe = commands.add_parser("describe", help="print the structure of a system "
                                   "description: components, connections, order, loops")
    describe.add_argument("config", help="a YAML or JSON system description, or an SSP "
                          "(.ssp archive or .ssd file)")
    describe.add_argument("--initialize", action="store_true",
                          help="initialize the system first (at run.t0, else 0)")
    describe.set_defaults(run=_describe_config)

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
    sweep.add_argument("--t0", type=float, default=None, dest="start_time",
                       help="start time in s (default: the system file's run.t0)")
    sweep.add_argument("--tf", type=float, default=None, dest="stop_time",
                       help="end time in s (default: run.tf)")
    sweep.add_argument("--dt", type=float, default=None, dest="step_size",
                       help="macro step in s (default: run.dt)")
    where = sweep.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, default=None, metavar="N",
                       help="worker processes of the embedded cluster (default: one per core)")
    where.add_argument("--scheduler", default=None, metavar="ADDR",
                       help="run on the Dask cluster of this scheduler, e.g. tcp://host:8786")
    sweep.add_argument("--member-timeout", type=float, default=None, metavar="S",
                       help="fail a member whose run takes longer than S seconds")
    sweep.add_argument("--output", "-o", type=Path, default=None, metavar="FILE",
                       help="write the results: .csv or .parquet (one row per member and "
                            "sample) or .nc (the xarray dataset)")
    sweep.add_argument("--quiet", action="store_true", dest="no_progress",
                       help="no progress bar")
    sweep.set_defaults(run=_sweep)
    return parser


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


def _resolve_fmu(name_or_path: str) -> Path:
    path = Path(name_or_path)
    if path.is_file():
        return path
    if path.suffix == "" and name_or_path in fmus.available():
        return Path(fmus.path(name_or_path))
    bundled = ", ".join(fmus.available()) or "none"
    raise CommandError(f"no FMU file {name_or_path!r} and no bundled FMU of that name "
                       f"(bundled: {bundled})")


def _read_description(path: Path) -> Any:
    from fmpy import read_model_description

    try:
        md = read_model_description(str(path), validate=False)
    except Exception as error:  # fmpy raises many kinds for a broken archive
        raise CommandError(f"{path} is not a readable FMU: {error}") from error
    if md.fmiVersion.startswith("3.") and md.coSimulation is not None:
        from .components.description_fmi3 import provides_directional_derivatives

        md.coSimulation.providesDirectionalDerivative = provides_directional_derivatives(path)
    return md


# ---------------------------------------------------------------------------------- info
def _info(args: argparse.Namespace, out: TextIO) -> None:
    path = _resolve_fmu(args.fmu)
    md = _read_description(path)
    out.write(f"Model:            {md.modelName}\n")
    if md.description:
        out.write(f"Description:      {md.description}\n")
    out.write(f"FMI version:      {md.fmiVersion}\n")
    out.write(f"GUID:             {md.guid}\n")
    if md.generationTool:
        out.write(f"Generation tool:  {md.generationTool}\n")
    out.write(f"File:             {path}\n")
    interfaces = [name for name, part in (("Co-Simulation", md.coSimulation),
                                          ("Model Exchange", md.modelExchange)) if part]
    out.write(f"Interfaces:       {', '.join(interfaces) or 'none'}\n")
    experiment = md.defaultExperiment
    if experiment is not None:
        fields = ("startTime", "stopTime", "stepSize", "tolerance")
        settings = [f"{f}={getattr(experiment, f)}" for f in fields
                    if getattr(experiment, f) is not None]
        out.write(f"Default experiment: {', '.join(settings) or 'none'}\n")
    if md.coSimulation is not None:
        out.write(f"\nCo-Simulation (model identifier {md.coSimulation.modelIdentifier}):\n")
        fmi3 = md.fmiVersion.startswith("3.")
        for capability in CAPABILITIES + (CAPABILITIES_FMI3 if fmi3 else ()):
            value = getattr(md.coSimulation, capability)
            out.write(f"  {capability:<40} {'yes' if value else 'no'}\n")
    rows = [
        (v.name, v.causality or "", v.variability or "", v.type or "", _unit(v),
         "" if v.start is None else str(v.start), v.description or "")
        for v in md.modelVariables
    ]
    out.write(f"\nVariables ({len(rows)}):\n")
    _write_table(out, ("name", "causality", "variability", "type", "unit", "start",
                       "description"), rows)
    feedthrough = {o: i for o, i in feedthrough_from_model_description(md).items() if i}
    out.write("\nDirect feedthrough:" + ("" if feedthrough else " none") + "\n")
    for output, inputs in feedthrough.items():
        out.write(f"  {output} <- {', '.join(sorted(inputs))}\n")


def _unit(variable: Any) -> str:
    """The unit, and the display unit where FMI 3.0 gives one ("m (display ft)")."""
    unit = variable.unit or getattr(variable.declaredType, "unit", None) or ""
    display = getattr(variable, "displayUnit", None) \
        or getattr(variable.declaredType, "displayUnit", None)
    return f"{unit} (display {display})" if display and display != unit else unit


def _write_table(out: TextIO, header: Sequence[str], rows: Sequence[Sequence[str]]) -> None:
    widths = [max(len(str(row[i])) for row in (header, *rows)) for i in range(len(header))]
    for row in (header, *rows):
        cells = [str(cell).ljust(width) for cell, width in zip(row, widths, strict=True)]
        out.write(("  " + "  ".join(cells)).rstrip() + "\n")


# ---------------------------------------------------------------------------------- fmus
def _list_fmus(args: argparse.Namespace, out: TextIO) -> None:
    names = fmus.available()
    if not names:
        raise CommandError("no bundled FMUs found (is syssimx built and installed?)")
    width = max(len(name) for name in names)
    for name in names:
        out.write(f"{name.ljust(width)}  {fmus.path(name)}\n")


# ---------------------------------------------------------------------------------- sweep
def _parameter_values(text: str) -> tuple[str, list[bool | int | float | str]]:
    from .ensemble.command import parameter_values

    return parameter_values(text)


def _sweep(args: argparse.Namespace, out: TextIO) -> None:
    from .ensemble.command import run_sweep

    run_sweep(args, out)


# ---------------------------------------------------------------------------------- simulate
def _simulate(args: argparse.Namespace, out: TextIO) -> None:
    from . import FMUComponent, JacobiAlgorithm, System
    from .components.model_description import read_fmu

    path = _resolve_fmu(args.fmu)
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
        source = _connect_input(system, component, args.input)
        # FMPy sets the inputs at the start of each step: the Jacobi coupling's timing
        system.set_algorithm(JacobiAlgorithm())
        # the engine integrates a Model Exchange FMU: any step is fine
        if source is not None and (component.model_exchange or
                                   md.coSimulation.canHandleVariableCommunicationStepSize):
            events = source.event_times().tolist()
    system.initialize(t0)
    result = _run(system, _communication_points(t0, tf, dt, events), dt) if events \
        else system.run(t0, tf, dt)

    t, values = result[component.name]
    columns = {name: values[name] for name, spec in component.output_specs.items()
               if name in values and str(getattr(spec.type, "value", spec.type)) != "event"}
    if args.output is not None:
        write_wide(args.output, t, columns, result.units[component.name])
        out.write(f"wrote {len(t)} samples of {len(columns)} outputs to {args.output}\n")
    if args.plot is not None:
        from .viz.plot import plot_result

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


# ---------------------------------------------------------------------------------- run
def _run_config(args: argparse.Namespace, out: TextIO) -> None:
    bar = not args.quiet and sys.stdout.isatty() and sys.stderr.isatty()
    options = {"progress": True} if bar else {}
    if _is_ssp(args.config):
        result = _run_ssp(args, options)
    else:
        from .system.config_source import Source, read_file
        from .system.loader import build_system, run_from_config, run_settings

        with _working_directory_importable():
            if args.algorithm is None and args.threads is None:
                result = run_from_config(args.config, t0=args.t0, tf=args.tf, dt=args.dt,
                                         progress=options.get("progress"))
            else:
                settings = run_settings(Source(Path(args.config)), read_file(args.config),
                                        {"t0": args.t0, "tf": args.tf, "dt": args.dt})
                system = build_system(args.config)
                _choose_algorithm(system, args)
                system.initialize(settings["t0"])
                result = system.run(settings["t0"], settings["tf"], settings["dt"], **options)
    out.write(f"Completed '{result.system_name}': t in [{result.t0}, {result.tf}] s, "
              f"dt = {result.dt} s, algorithm = {result.algorithm}, "
              f"wall time = {result.wall_time:.3f} s\n")
    termination = result.termination
    if termination is not None:  # a component asked to stop: the end of the run, not a failure
        out.write(f"{termination}\n")
    if args.output is not None:
        out.write(f"Results written to {result.to_csv(args.output)}\n")


# ---------------------------------------------------------------------------------- describe
def _describe_config(args: argparse.Namespace, out: TextIO) -> None:
    from .system.loader import build_system, load_config

    if _is_ssp(args.config):
        from .ssp import read

        imported = read(args.config)
        if args.initialize:
            imported.system.initialize(_choose(None, imported.experiment.start_time, 0.0))
        out.write(imported.system.describe() + "\n")
        return
    with _working_directory_importable():
        system = build_system(args.config)
    if args.initialize:
        run = load_config(args.config).get("run") or {}
        system.initialize(float(run.get("t0", 0.0)) if isinstance(run, dict) else 0.0)
    out.write(system.describe() + "\n")


def _is_ssp(path: str) -> bool:
    return Path(path).suffix.lower() in SSP_SUFFIXES


def _algorithm(name: str) -> Any:
    from . import GaussSeidelAlgorithm, HybridAlgorithm, JacobiAlgorithm

    return {"jacobi": JacobiAlgorithm, "gauss_seidel": GaussSeidelAlgorithm,
            "hybrid": HybridAlgorithm}[name]()


def _choose_algorithm(system: Any, args: argparse.Namespace) -> None:
    """--algorithm replaces the description's algorithm; --threads sets its threads."""
    if args.algorithm is None and args.threads is None:
        return
    algorithm = _algorithm(args.algorithm) if args.algorithm is not None else system.algorithm
    if args.threads is not None:
        coupling = getattr(algorithm, "coupling", algorithm)  # a hybrid algorithm's coupling
        coupling.threads = args.threads
    system.set_algorithm(algorithm)


def _run_ssp(args: argparse.Namespace, options: dict[str, Any]) -> Any:
    """An SSP's system over its default experiment (start 0 when it has none); the stop time
    and the step come from the experiment, the OSP fixed-step annotation, or the options."""
    from .ssp import read

    imported = read(args.config)
    experiment = imported.experiment
    t0 = _choose(args.t0, experiment.start_time, 0.0)
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


@contextmanager
def _working_directory_importable() -> Iterator[None]:
    """Component classes ("module:Class") are also found in the working directory, as with
    SysSimX's command line: a console script's sys.path does not have it."""
    saved = list(sys.path)
    sys.path.insert(0, os.getcwd())
    try:
        yield
    finally:
        sys.path[:] = saved


def _experiment(args: argparse.Namespace, experiment: Any, fixed_step: str | None = None
                ) -> tuple[float, float, float]:
    """Start, stop and step: given, else from the default experiment, else FMPy's defaults.
    FMPy steps an FMI 3.0 FMU with a fixedInternalStepSize by that step first."""
    t0 = _choose(args.start_time, getattr(experiment, "startTime", None), 0.0)
    tf = _choose(args.stop_time, getattr(experiment, "stopTime", None), t0 + 1.0)
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


def _communication_points(t0: float, tf: float, dt: float, events: Any) -> list[float]:
    """FMPy's steps for an FMU that can vary its step: the grid t0 + k*dt plus every input
    event between grid points (one within 1e-9 relative of a grid point is that point)."""
    points, regular_steps, t = [t0], 0, t0
    while not (t > tf or math.isclose(t, tf)):
        regular = t0 + (regular_steps + 1) * dt
        upcoming = next((e for e in events if e > t and not math.isclose(e, t)), math.inf)
        step_end = upcoming if regular > upcoming and not math.isclose(regular, upcoming) \
            else regular
        t = tf if step_end > tf and not math.isclose(step_end, tf) else step_end
        points.append(t)
        regular_steps += math.isclose(t, regular)
    return points


def _run(system: Any, points: list[float], dt: float) -> Any:
    """Runs through the communication points: stretches of regular steps of dt in one run each,
    every step off that grid (to or from an input event, to the stop time) in a run of its own;
    stops when a component terminates."""
    start, result = points[0], None
    for previous, point in itertools.pairwise(points):
        if math.isclose(point - previous, dt):
            continue
        if previous > start:
            result = system.run(start, previous, dt)
            if result.termination is not None:
                return result
        result = system.run(previous, point, point - previous)
        if result.termination is not None:
            return result
        start = point
    if points[-1] > start:
        result = system.run(start, points[-1], dt)
    return result


def _connect_input(system: Any, component: Any, csv_path: Path) -> TableSource | None:
    """A table source from the CSV file, its columns connected to the inputs of the same name;
    each column is read as the input's type, held where FMPy holds it (non-continuous)."""
    from . import Connection, TableSource
    from .components.time_table import read_time_table

    table = read_time_table(csv_path, "--input")
    inputs = {n: s for n, s in component.input_specs.items() if s.type in _TABLE_DTYPES}
    used = [name for name in table.columns if name in inputs]
    ignored = [name for name in table.columns if name not in inputs]
    if ignored:
        print(f"syssimx: warning: {csv_path}: {', '.join(ignored)} "
              f"{'names' if len(ignored) == 1 else 'name'} no input of {component.name}; "
              "ignored", file=sys.stderr)
    if not used:
        return None
    columns = [("time", np.float64), *((n, _TABLE_DTYPES[inputs[n].type]) for n in used)]
    signals = np.empty(len(table.time), dtype=columns)
    signals["time"] = table.time
    for name in used:
        values, kind = table.columns[name][1], inputs[name].type
        if kind == PortType.REAL:
            signals[name] = values
        else:  # FMPy casts the column to the input's C int (truncating); a boolean is non-zero
            if kind == PortType.INT:
                _check_integer_column(csv_path, name, table.time, values)
            truncated = values.astype(np.int32)
            signals[name] = truncated if kind == PortType.INT else truncated != 0
    hold = [n for n in used if inputs[n].type == PortType.REAL
            and component.info.variables[n].variability in ("discrete", "tunable")]
    source = TableSource(csv_path.name, signals, hold=hold)  # numbers in the inputs' units
    system.add_component(source)
    for name in used:
        system.add_connection(Connection(source.name, name, component.name, name))
    return source


def _check_integer_column(csv_path: Path, name: str, time: np.ndarray, values: np.ndarray
                          ) -> None:
    """An Integer input takes C ints (an FMI 3.0 UInt32 or 64-bit input too): a value beyond
    them is refused, not wrapped."""
    limits = np.iinfo(np.int32)
    outside = np.flatnonzero((values < limits.min) | (values > limits.max))
    if len(outside):
        k = int(outside[0])
        raise CommandError(f"--input {csv_path}: column {name!r} holds {values[k]:.17g} at "
                           f"t = {float(time[k])!r}, outside the range of syssimx's Integer ports "
                           f"({limits.min}..{limits.max})")


def _choose(given: float | None, default: Any, fallback: float) -> float:
    if given is not None:
        return float(given)
    return float(default) if default is not None else fallback


def _event_name(variable: str) -> str:
    return f"{variable}_crossing"


if __name__ == "__main__":
    sys.exit(main())
