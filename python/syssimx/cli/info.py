"""`syssimx info`: an FMU's description, capabilities, variables and direct feedthrough."""

from __future__ import annotations

import argparse
import zipfile
from collections.abc import Sequence
from pathlib import Path
from typing import Any, TextIO

from ..graph.analysis import feedthrough_from_model_description
from .common import CommandError, resolve_fmu

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


def add_command(commands: Any) -> argparse.ArgumentParser:
    info = commands.add_parser("info", help="describe an FMU: variables and capabilities")
    info.add_argument("fmu", help="path to a .fmu file, or the name of a bundled FMU")
    info.set_defaults(run=run_info)
    return info


def run_info(args: argparse.Namespace, out: TextIO) -> None:
    path = resolve_fmu(args.fmu)
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


def _read_description(path: Path) -> Any:
    from fmpy import read_model_description

    from ..fmu.description import check_declared_size

    try:
        with zipfile.ZipFile(path) as archive:  # FMPy reads the description whole
            check_declared_size(sum(entry.file_size for entry in archive.infolist()
                                    if entry.filename == "modelDescription.xml"), path)
        md = read_model_description(str(path), validate=False)
    except Exception as error:  # fmpy raises many kinds for a broken archive
        raise CommandError(f"{path} is not a readable FMU: {error}") from error
    if md.fmiVersion.startswith("3.") and md.coSimulation is not None:
        from ..fmu.description_fmi3 import provides_directional_derivatives

        md.coSimulation.providesDirectionalDerivative = provides_directional_derivatives(path)
    return md


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
