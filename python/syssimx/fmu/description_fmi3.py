"""FMI 3.0 modelDescription.xml, read with FMPy's reader and checked for what syssimx runs.

The engine's one-pass reader (description_reader.py) is FMI 2.0's: FMI 3.0 names a variable by
its type element (`<Float64>`, `<Int8>`, ...), gives it dimensions, clocks and aliases, and
states ModelStructure by value reference. FMPy reads all of that into the same objects (fmpy's
attribute names), so the rest of syssimx reads an FMI 3.0 description like an FMI 2.0 one.

syssimx steps FMI 3.0 Co-Simulation FMUs and integrates FMI 3.0 Model Exchange ones. It
reads every Clock (clocks.py) and refuses, naming the file and the element: scheduled execution
only, a Clock the engine does not tick (naming the clock and why: it ticks periodic input
clocks, and in Co-Simulation with event mode triggered input clocks and output clocks), and
String or Binary arrays among the inputs, outputs and parameters. Numeric and Boolean arrays
become one port per element, made when asked for (fmi3_arrays.py).

A description is data: every value reference, dimension and start value is checked here, and
an FMUFileError names the file and the variable, before anything is sized by it. The arrays of
one FMU hold at most MAX_ARRAY_ELEMENTS elements together.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from ..core.element_map import Block
from ..engine import ffi
from ..errors import FMUFileError
from .clocks import ClockInfo, ClockStructure, read_clocks
from .fmi3_arrays import ArrayPort

logger = logging.getLogger("syssimx.fmu")

if TYPE_CHECKING:  # fmpy is imported by the first read, not with syssimx
    from fmpy.model_description import ModelDescription

# the FMI 3.0 types syssimx exchanges, by the engine's ssx_fmi3_type code
FMI3_TYPE_CODES = {"Float64": 0, "Float32": 1, "Int8": 2, "UInt8": 3, "Int16": 4, "UInt16": 5,
                   "Int32": 6, "UInt32": 7, "Int64": 8, "UInt64": 9, "Boolean": 10,
                   "Enumeration": 8}  # FMI 3.0 enumerations are exchanged as Int64
_PORT_CAUSALITIES = ("input", "output", "parameter")
MAX_ARRAY_ELEMENTS = 1_000_000  # all arrays of one FMU together
MAX_VALUE_REFERENCE = 2**32 - 1
_INTEGER_RANGES = {"Int8": (-2**7, 2**7 - 1), "UInt8": (0, 2**8 - 1),
                   "Int16": (-2**15, 2**15 - 1), "UInt16": (0, 2**16 - 1),
                   "Int32": (-2**31, 2**31 - 1), "UInt32": (0, 2**32 - 1),
                   "Int64": (-2**63, 2**63 - 1), "UInt64": (0, 2**64 - 1),
                   "Enumeration": (-2**63, 2**63 - 1)}


class FMI3Variable(NamedTuple):
    """A scalar row of the engine's FMI 3.0 table: value reference, ssx_fmi3_type code,
    name."""

    value_reference: int
    type_code: int
    name: str


class EngineTable(NamedTuple):
    """What the engine's FMI 3.0 table is made of: the scalar rows and the array ports (a row
    per element, made by engine_variables)."""

    scalars: list[FMI3Variable]
    arrays: list[ArrayPort]


def read_fmi3_description(path: Path) -> ModelDescription:
    """The FMI 3.0 description of the FMU archive at `path`; FMUFileError naming the file and
    the element when syssimx cannot run it."""
    from fmpy import read_model_description

    try:
        description = read_model_description(str(path), validate=False)
    except Exception as exc:  # fmpy raises many kinds for a broken description
        raise FMUFileError(f"{path}: modelDescription.xml declares FMI 3.0 but is not a "
                           f"readable FMI 3.0 description ({type(exc).__name__}: {exc})"
                           ) from exc
    elements = 0
    for variable in description.modelVariables:
        _check_variable(variable, path)
        if variable.dimensions:
            elements += math.prod(variable.shape)
            if elements > MAX_ARRAY_ELEMENTS:
                raise FMUFileError(f"{path}: array {_quoted(variable.name)} of shape "
                                   f"{tuple(variable.shape)} takes the FMU's array elements "
                                   f"past syssimx's limit of {MAX_ARRAY_ELEMENTS}")
    clocks = clock_structure(path)
    if description.coSimulation is None and description.modelExchange is None:
        if description.scheduledExecution is not None:
            raise FMUFileError(f"{path}: FMI 3.0 Scheduled Execution is not supported as a "
                               "Co-Simulation or Model Exchange component (syssimx runs FMI "
                               "3.0 Co-Simulation and Model Exchange FMUs without clocks)")
        raise FMUFileError(f"{path}: the FMI 3.0 description declares neither CoSimulation nor "
                           "ModelExchange")
    _refuse_clocks(clocks, path, description.coSimulation, description.modelExchange)
    if description.instantiationToken is None:
        raise FMUFileError(f"{path}: the FMI 3.0 description has no instantiationToken")
    if not description.instantiationToken:
        # FMPy 0.3.32's FMI 3.0 containers write instantiationToken="", and their binaries
        # accept it: the binary is the judge of the token it is handed
        logger.warning("%s: the FMI 3.0 description's instantiationToken is empty; the FMU "
                       "is instantiated with the empty token", path)
    # fmpy keeps FMI 3.0's token under both names; syssimx passes it where FMI 2.0 has the guid
    description.guid = description.instantiationToken
    # the engine's references of array elements are not the FMU's: with array ports the
    # engine takes finite differences instead of asking the FMU for directional derivatives
    has_array_ports = any(v.dimensions and v.causality in _PORT_CAUSALITIES
                          for v in description.modelVariables)
    for element, part in (("CoSimulation", description.coSimulation),
                          ("ModelExchange", description.modelExchange)):
        if part is not None:
            part.providesDirectionalDerivative = \
                provides_directional_derivatives(path, element) and not has_array_ports
    return description


def _refuse_clocks(clocks: ClockStructure, path: Path, cosimulation: Any = None,
                   model_exchange: Any = None) -> None:
    """FMUFileError naming the first clock no interface of the FMU can tick: periodic input
    clocks (intervalVariability constant or fixed, the interval in the description) of a
    Co-Simulation FMU with event mode and of a Model Exchange FMU; triggered, countdown, tunable
    and changing input clocks and output clocks of a Co-Simulation FMU with event mode; no
    other clock."""
    rules = []
    if cosimulation is not None and cosimulation.hasEventMode:
        rules.append(_cosimulation_clock)
    if model_exchange is not None:
        rules.append(_periodic_input)
    untickable = [c for c in clocks.clocks if not any(rule(c) for rule in rules)]
    if untickable:
        _refuse(untickable[0], path)


def _refuse(clock: ClockInfo, path: Path) -> None:
    if clock.causality not in ("input", "output"):
        why = "a local clock is the FMU's own"
    else:
        why = ("syssimx ticks periodic input clocks (intervalVariability constant or fixed) "
               "of FMI 3.0 Co-Simulation FMUs with event mode and of Model Exchange FMUs, and "
               "triggered, countdown, tunable and changing input clocks and output clocks "
               "(triggered) of Co-Simulation FMUs with event mode only")
    raise FMUFileError(f"{path}: Clock {clock.name!r} ({clock.causality}, "
                       f"intervalVariability {clock.interval_variability}) is not supported: "
                       f"{why}")


# the clocks whose interval the FMU announces (fmi3GetIntervalDecimal); all but countdown repeat
_ANNOUNCED = ("countdown", "tunable", "changing")


def _periodic_input(clock: ClockInfo) -> bool:
    return (clock.causality == "input" and clock.interval_variability in ("constant", "fixed")
            and clock.period is not None)


def _cosimulation_clock(clock: ClockInfo) -> bool:
    """A clock the engine ticks or reads in Co-Simulation with event mode: a periodic input
    clock, a triggered input clock (ticked by what it is connected to), a countdown, tunable or
    changing input clock (ticked when the interval the FMU announces has passed) or an output
    clock (read in every Event Mode)."""
    return _periodic_input(clock) or (clock.interval_variability == "triggered"
                                      and clock.causality in ("input", "output")) or (
        clock.interval_variability in _ANNOUNCED and clock.causality == "input")


def ticked_clocks(clocks: ClockStructure, interface: str, path: Path,
                  cosimulation: Any = None) -> tuple[ClockInfo, ...]:
    """The clocks the engine ticks or reads in `interface`; FMUFileError naming the first
    clock it cannot tick there (any clock of a Co-Simulation FMU without event mode, which has
    no instant to tick it at; any but a periodic input clock in Model Exchange)."""
    if interface == "model-exchange":
        untickable = [c for c in clocks.clocks if not _periodic_input(c)]
    elif cosimulation is None or not cosimulation.hasEventMode:
        untickable = list(clocks.clocks)
    else:
        untickable = [c for c in clocks.clocks if not _cosimulation_clock(c)]
    if untickable:
        _refuse(untickable[0], path)
    return clocks.clocks


def triggered_input_clocks(clocks: Sequence[ClockInfo]) -> list[ClockInfo]:
    """The triggered input clocks, in the engine's order (its clock indices)."""
    return [c for c in clocks
            if c.causality == "input" and c.interval_variability == "triggered"]


def output_clocks(clocks: Sequence[ClockInfo]) -> list[ClockInfo]:
    """The output clocks, in the engine's order (its clock indices)."""
    return [c for c in clocks if c.causality == "output"]


def clock_structure(path: Path) -> ClockStructure:
    """The clocks of the FMI 3.0 FMU archive `path`, whatever interfaces it has."""
    return read_clocks(_description_root(path), path)


def provides_directional_derivatives(path: Path, element: str = "CoSimulation") -> bool:
    """FMI 3.0 spells the flag providesDirectionalDerivatives, which FMPy 0.3 does not read;
    `element`: the interface's (CoSimulation or ModelExchange)."""
    found = _description_root(path).find(element)
    return found is not None and found.get("providesDirectionalDerivatives") in ("true", "1")


def intermediate_inputs(path: Path) -> list[int]:
    """Value references of the scalar continuous Float64 inputs with intermediateUpdate="true"
    (an attribute FMPy 0.3 does not read): FMI 3.0 moves inputs inside a step by intermediate
    update, which the engine answers for these as FMI 2.0's input derivatives."""
    variables = _description_root(path).find("ModelVariables")
    if variables is None:
        return []
    found = []
    for variable in variables.findall("Float64"):
        if variable.get("causality") == "input" and variable.get("intermediateUpdate") in \
                ("true", "1") and variable.find("Dimension") is None and \
                variable.get("variability", "continuous") == "continuous":
            reference = variable.get("valueReference", "")
            if reference.isdigit():
                found.append(int(reference))
    return found


def _description_root(path: Path) -> Any:
    import zipfile

    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True)
    with zipfile.ZipFile(path) as archive:
        return etree.fromstring(archive.read("modelDescription.xml"), parser)


def _check_variable(variable: Any, path: Path) -> None:
    name = _quoted(variable.name)
    vr = variable.valueReference
    if not isinstance(vr, int) or not 0 <= vr <= MAX_VALUE_REFERENCE:
        raise FMUFileError(f"{path}: variable {name} has valueReference {_quoted(vr)}; FMI 3.0 "
                           f"value references are 0 to {MAX_VALUE_REFERENCE}")
    for extent, dimension in zip(variable.shape or (), variable.dimensions or (), strict=False):
        if extent < 0:
            source = f"structural parameter {_quoted(dimension.variable.name)}" \
                if dimension.variable is not None else "its start"
            raise FMUFileError(f"{path}: variable {name} has a dimension of {extent} (from "
                               f"{source}); a dimension is 0 or more")
    _check_start(variable, path)
    if variable.dimensions and variable.causality in _PORT_CAUSALITIES \
            and variable.type in ("String", "Binary"):
        raise FMUFileError(f"{path}: variable {variable.name!r} is a {variable.type} array "
                           f"({variable.causality}): String and Binary arrays are not "
                           "supported (numeric and Boolean arrays are)")


def _check_start(variable: Any, path: Path) -> None:
    """The start value parses as the variable's type: each element's for an array."""
    if variable.start is None or variable.type in ("String", "Clock"):
        return
    text = str(variable.start)
    if variable.type == "Binary":
        hex_digits = "".join(text.split())
        if len(hex_digits) % 2 or any(c not in "0123456789abcdefABCDEF" for c in hex_digits):
            raise FMUFileError(f"{path}: variable {_quoted(variable.name)}: Binary start "
                               f"{_quoted(text)} is not an even number of hexadecimal digits")
        return
    for value in text.split():  # an array's count of values: fmi3_arrays.py
        if not _parses(variable.type, value):
            raise FMUFileError(f"{path}: variable {_quoted(variable.name)}: start "
                               f"{_quoted(value)} is not a {variable.type} value")


def _parses(fmi_type: str, text: str) -> bool:
    if fmi_type in ("Float64", "Float32"):
        try:
            float(text)
        except ValueError:
            return False
        return True
    if fmi_type == "Boolean":
        return text in ("true", "false", "1", "0")
    if fmi_type in _INTEGER_RANGES:
        low, high = _INTEGER_RANGES[fmi_type]
        try:
            return low <= int(text) <= high
        except ValueError:
            return False
    return True


def _quoted(value: Any) -> str:
    """repr of a name or value from the file, cut short: a message never grows with it."""
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


def engine_table(in_order: list[Any]) -> EngineTable:
    """The engine's FMI 3.0 type table of the variables `in_order` (array_variables'): each
    numeric or Boolean scalar once per value reference (an alias shares its variable's), and
    the array ports; arrays no port carries (locals) are left out."""
    table: dict[int, FMI3Variable] = {}
    arrays = []
    for variable in in_order:
        if isinstance(variable, ArrayPort):
            arrays.append(variable)
            continue
        code = FMI3_TYPE_CODES.get(variable.type)
        if code is not None and not variable.dimensions:
            vr = variable.valueReference
            table.setdefault(vr, FMI3Variable(vr, code, variable.name))
    return EngineTable(list(table.values()), arrays)


def engine_variables(table: EngineTable, cosimulation: Any, model_exchange: bool,
                     intermediate: tuple[int, ...] = (),
                     clocks: tuple[ClockInfo, ...] = ()) -> tuple[Any, list[Any]]:
    """The ssx_fmi3_variables of `table` and of how a Co-Simulation instance is made (event
    mode when the FMU has it, early return when it may return early, the inputs it moves by
    intermediate update), and what it points at: the struct does not keep that alive, the
    caller does until the engine copied it. An array's rows are filled from numpy, a column
    at a time, and its elements' names go to one pool."""
    scalars, arrays = table
    count = len(scalars) + sum(a.size for a in arrays)
    columns = {"vr": ffi.new("unsigned int[]", count), "type": ffi.new("unsigned char[]", count)}
    vr = np.frombuffer(ffi.buffer(columns["vr"]), np.uint32)
    kind = np.frombuffer(ffi.buffer(columns["type"]), np.uint8)
    n = len(scalars)
    vr[:n] = [row.value_reference for row in scalars]
    kind[:n] = [row.type_code for row in scalars]
    names = [row.name for row in scalars]
    for array in arrays:
        vr[n:n + array.size] = np.arange(array.first_vr, array.first_vr + array.size)
        kind[n:n + array.size] = FMI3_TYPE_CODES[array.variable.type]
        names.extend(Block(array.name, array.shape, array.element).names())
        n += array.size
    pool = ffi.new("char[]", b"\0".join(name.encode() for name in names) + b"\0")
    lengths = np.fromiter((len(name.encode()) + 1 for name in names), np.intp, count)
    columns["name"] = ffi.new("const char *[]", count)
    np.frombuffer(ffi.buffer(columns["name"]), np.uintp)[:] = \
        int(ffi.cast("uintptr_t", pool)) + np.concatenate(([0], np.cumsum(lengths)[:-1]))
    fields: dict[str, Any] = {
        **columns, "n": count,
        "event_mode_used": not model_exchange and bool(cosimulation.hasEventMode),
        "early_return_allowed": not model_exchange and bool(
            cosimulation.canReturnEarlyAfterIntermediateUpdate
            or cosimulation.mightReturnEarlyFromDoStep)}
    periodic = [c for c in clocks if _periodic_input(c)]
    if periodic:  # periodic input clocks the engine ticks (ticked_clocks)
        fields.update({
            "clock_vr": ffi.new("unsigned int[]", [c.value_reference for c in periodic]),
            "clock_period": ffi.new("double[]", [c.period for c in periodic]),
            "clock_shift": ffi.new("double[]", [c.first_tick for c in periodic]),
            "n_clocks": len(periodic)})
    triggered = triggered_input_clocks(clocks)
    if triggered and not model_exchange:  # ticked by what they are connected to
        fields.update({"triggered_clock_vr": ffi.new(
            "unsigned int[]", [c.value_reference for c in triggered]),
            "n_triggered_clocks": len(triggered)})
    countdown = [c for c in clocks
                 if c.causality == "input" and c.interval_variability in _ANNOUNCED]
    if countdown and not model_exchange:  # ticked when their announced interval has passed
        fields.update({
            "countdown_clock_vr": ffi.new("unsigned int[]",
                                          [c.value_reference for c in countdown]),
            "countdown_clock_repeats": ffi.new(
                "unsigned char[]", [c.interval_variability != "countdown" for c in countdown]),
            "n_countdown_clocks": len(countdown)})
    outputs = output_clocks(clocks)
    if outputs and not model_exchange:  # read in every Event Mode
        fields.update({"output_clock_vr": ffi.new(
            "unsigned int[]", [c.value_reference for c in outputs]),
            "n_output_clocks": len(outputs)})
    if intermediate and not model_exchange:  # inputs the engine moves inside a step
        fields.update({"intermediate_vr": ffi.new("unsigned int[]", list(intermediate)),
                       "n_intermediate": len(intermediate)})
    if arrays:  # where each element lies; a scalar's size is 0
        where = {"fmu_vr": ffi.new("unsigned int[]", count),
                 "element": ffi.new("size_t[]", count), "size": ffi.new("size_t[]", count),
                 "start": ffi.new("double[]", count)}
        fmu_vr = np.frombuffer(ffi.buffer(where["fmu_vr"]), np.uint32)
        element = np.frombuffer(ffi.buffer(where["element"]), np.uintp)
        size = np.frombuffer(ffi.buffer(where["size"]), np.uintp)
        start = np.frombuffer(ffi.buffer(where["start"]), np.float64)
        n = len(scalars)
        fmu_vr[:n] = vr[:n]
        for array in arrays:
            part = slice(n, n + array.size)
            fmu_vr[part] = array.variable.valueReference
            element[part] = np.arange(array.size)
            size[part] = array.size
            if array.starts is not None:
                start[part] = array.starts.astype(np.float64)
            n += array.size
        fields.update(where)
    return ffi.new("ssx_fmi3_variables *", fields), [columns, pool, fields]
