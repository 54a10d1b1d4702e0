"""What syssimx needs from an FMU archive: validated files, ports, parameters, feedthrough.

Everything here is checked before an FMU is loaded, so a broken, foreign or hostile .fmu gives
a clear error naming the file and what is wrong with it.
"""

from __future__ import annotations

import logging
import math
import os
import zipfile
import zlib
from collections.abc import Iterable, Mapping, MutableMapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple

from ..core.element_map import Block, ElementMap
from ..core.port import PortSpec, PortType
from ..errors import FMUFileError
from ..graph.analysis import feedthrough_from_model_description, undeclared_outputs
from ..units import plainly_readable, to_unit
from .archive import open_archive
from .clocks import ClockStructure
from .description import Described, read_description
from .description_fmi3 import EngineTable, clock_structure
from .fmi3_arrays import ArrayPort
from .standards import Standard
from .unit_definitions import unit_definitions
from .variable_table import ScalarVariable, VariableTable

if TYPE_CHECKING:
    from fmpy.model_description import ModelDescription

logger = logging.getLogger("syssimx.fmu")

# the engine's port type of each FMI 2.0 and FMI 3.0 value type: the integers a C int holds
# are Integer ports, the wider ones Real ports (exact up to 2**53, a value beyond fails naming
# the variable)
PORT_TYPES = {"Real": PortType.REAL, "Integer": PortType.INT, "Enumeration": PortType.INT,
               "Boolean": PortType.BOOL, "Float64": PortType.REAL, "Float32": PortType.REAL,
               **dict.fromkeys(("Int8", "UInt8", "Int16", "UInt16", "Int32"), PortType.INT),
               **dict.fromkeys(("UInt32", "Int64", "UInt64"), PortType.REAL)}


class Parameter(NamedTuple):
    """A settable FMU parameter (causality "parameter"; also a String or, FMI 3.0, Binary
    input, which no port carries). Immutable; a tuple because a large model has 10**5 of them
    and a tuple is made in half the time of a frozen dataclass. `fmi_type` is the variable's
    type element ("Real", "Float32", "String", "Binary", ...)."""

    name: str
    value_reference: int
    type: PortType
    unit: str | None
    tunable: bool
    start: float | int | bool | str | bytes | None
    fmi_type: str = ""


class FMUInterface(NamedTuple):
    """One interface of the FMU (FMPy's CoSimulation or ModelExchange element)."""

    name: str  # "co-simulation" or "model-exchange"
    model_identifier: str  # names its binary
    can_get_set_state: bool
    provides_directional_derivative: bool
    can_be_instantiated_only_once_per_process: bool
    # Co-Simulation only (FMI 2.0 input derivatives; output derivatives in 2.0 and 3.0)
    can_interpolate_inputs: bool = False
    max_output_derivative_order: int = 0
    intermediate_inputs: tuple[int, ...] = ()  # FMI 3.0: inputs moved by intermediate update


INTERFACES = ("co-simulation", "model-exchange")  # "auto" takes the first the FMU has


@dataclass
class FMUInfo:
    """The facts of one FMU archive syssimx uses."""

    path: Path
    description: ModelDescription
    model_identifier: str
    can_get_set_state: bool
    variables: Mapping[str, ScalarVariable]  # looked up by name, made when asked for
    default_tolerance: float | None = None  # DefaultExperiment tolerance
    # the maps below make an FMI 3.0 array's elements when they are asked for
    input_specs: MutableMapping[str, PortSpec] = field(default_factory=ElementMap)
    output_specs: MutableMapping[str, PortSpec] = field(default_factory=ElementMap)
    parameters: MutableMapping[str, Parameter] = field(default_factory=ElementMap)
    # 0 if none given ("" for a String input, b"" for a Binary one)
    input_starts: MutableMapping[str, float | int | bool | str | bytes] = field(
        default_factory=ElementMap)
    # of ports and parameters
    value_references: MutableMapping[str, int] = field(default_factory=ElementMap)
    feedthrough: MutableMapping[str, set[str]] = field(default_factory=ElementMap)
    # outputs (variables) whose dependencies ModelStructure does not declare: their
    # feedthrough is the standard's assumption, every input
    undeclared_outputs: set[str] = field(default_factory=set)
    interfaces: dict[str, FMUInterface] = field(default_factory=dict)  # by INTERFACES name
    # Model Exchange: ModelStructure/Derivatives, numberOfEventIndicators (FMI 3.0:
    # ModelStructure/EventIndicator)
    number_of_states: int = 0
    number_of_event_indicators: int = 0
    standard: Standard = field(default_factory=Standard)  # the FMI version's
    # FMI 3.0: every scalar the engine may get or set and the array ports, and each
    # structural parameter with the arrays it sizes
    fmi3_variables: EngineTable = field(default_factory=lambda: EngineTable([], []))
    structural_parameters: dict[str, list[str]] = field(default_factory=dict)
    # every variable (FMI 3.0: its array ports as elements), made when iterated
    all_variables: Iterable[Any] = ()
    # each name several variables have -> their value references: no port or parameter
    ambiguous_names: dict[str, list[int]] = field(default_factory=dict)
    # FMI 3.0: the Clock variables, the clocked variables and the clock dependencies
    clocks: ClockStructure = field(default_factory=ClockStructure)

    def binary_name(self, interface: str | None = None) -> str:
        """The binary of `interface` (None: the one "auto" takes)."""
        identifier = self.model_identifier if interface is None \
            else self.interfaces[interface].model_identifier
        return self.standard.binary_name(identifier)


def variable_unit(variable: ScalarVariable) -> str | None:
    """The variable's unit, inherited from its declaredType when the variable has none."""
    if variable.unit:
        return variable.unit
    declared = variable.declaredType
    return getattr(declared, "unit", None) or None


def _pint_unit(unit: str) -> str | None:
    """`unit` if pint reads it, else its lower-case spelling (e.g. "Ohm") if pint reads that,
    else None."""
    if plainly_readable(unit):
        return unit
    for candidate in (unit, unit.lower()):
        try:
            to_unit(candidate)
            return candidate
        except ValueError:
            continue
    return None


def _start_value(variable: ScalarVariable, kind: PortType
                 ) -> float | int | bool | str | bytes | None:
    start: Any = variable.start
    if start is None:
        return None
    if variable.type == "Binary":
        return bytes.fromhex(start.strip())
    text = start.strip()
    if kind == PortType.REAL:
        return float(text)
    if kind == PortType.INT:
        return int(text)
    if kind == PortType.BOOL:
        return text in ("true", "1")
    return str(start)


class _FileStamp(NamedTuple):
    """What tells a changed file: rewritten in place or replaced, its size or mtime differs."""

    size: int
    mtime_ns: int


# absolute path -> the stamp it was read at and what was read; one entry per FMU file, replaced
# when the file changes. Components copy what they change, so the FMUInfo is shared as is.
_read_cache: dict[str, tuple[_FileStamp, FMUInfo]] = {}


def read_fmu(fmu_path: str | Path) -> FMUInfo:
    """Validate the archive and read its model description (no extraction, no loading).

    Each file is read once per process: a later call for an unchanged file (same size and
    mtime) returns the same FMUInfo, which callers must not modify.
    """
    key = os.path.abspath(fmu_path)  # resolving symlinks costs more than the rest of a hit
    try:
        status = os.stat(key)
    except OSError:
        return _read_fmu(Path(key).resolve())  # open_archive names what is wrong with the path
    stamp = _FileStamp(status.st_size, status.st_mtime_ns)
    cached = _read_cache.get(key)
    if cached is not None and cached[0] == stamp:
        return cached[1]
    info = _read_fmu(Path(key).resolve())
    _read_cache[key] = (stamp, info)
    return info


def _read_fmu(path: Path) -> FMUInfo:
    with open_archive(path) as archive:
        names = set(archive.namelist())
        if "modelDescription.xml" not in names:
            raise FMUFileError(f"{path} is not an FMU: the archive has no modelDescription.xml")
        standard, description = _read_description(archive, path)
        interfaces = _interfaces(description, path)
        first = interfaces[next(n for n in INTERFACES if n in interfaces)]
        # only the ports become objects: a large model's locals stay in the reader's arrays
        variables = standard.variables(description, path)
        info = FMUInfo(path=path, description=description,
                       model_identifier=first.model_identifier,
                       can_get_set_state=first.can_get_set_state,
                       variables=variables.by_name,
                       default_tolerance=_default_tolerance(description, path),
                       interfaces=interfaces,
                       number_of_states=description.numberOfContinuousStates,
                       number_of_event_indicators=description.numberOfEventIndicators,
                       standard=standard, fmi3_variables=variables.engine_table,
                       structural_parameters=variables.structural,
                       clocks=clock_structure(path) if standard.engine_version == 3
                       else ClockStructure())
        if info.binary_name() not in names:
            raise FMUFileError(f"{path} has no {standard.platform} binary "
                               f"({info.binary_name()} missing)")
    info.all_variables = variables.all
    info.ambiguous_names = _ambiguous_names(description.modelVariables, path)
    _collect_ports_and_parameters(info, variables.ports)
    _collect_feedthrough(info, variables.ports, variables.outputs)
    return info


def _ambiguous_names(variables: Any, path: Path) -> dict[str, list[int]]:
    """The names several variables have (the standard forbids it, but FMPy and libcosim run
    such FMUs), warned about once: they become no port or parameter, so the rest of the FMU
    runs and only addressing one of them is an error."""
    if isinstance(variables, VariableTable):
        found = variables.duplicates()
    else:
        references: dict[str, list[int]] = {}
        for variable in variables:
            references.setdefault(variable.name, []).append(variable.valueReference)
        found = {name: vrs for name, vrs in references.items() if len(vrs) > 1}
    if found:
        listed = ", ".join(f"{name!r} (value references {', '.join(map(str, vrs))})"
                           for name, vrs in found.items())
        logger.warning("%s: the modelDescription names several variables alike: %s; syssimx "
                       "leaves them out (addressing one of these names is an error)",
                       path.name, listed)
    return found


def _read_description(archive: zipfile.ZipFile, path: Path) -> Described:
    try:
        with archive.open("modelDescription.xml") as stream:
            declared_size = archive.getinfo("modelDescription.xml").file_size
            return read_description(stream, path, declared_size)
    except (zipfile.BadZipFile, zlib.error, EOFError, NotImplementedError, OSError) as exc:
        raise FMUFileError(f"{path}: cannot read modelDescription.xml from the archive: "
                           f"{exc or type(exc).__name__}") from exc


def _default_tolerance(description: ModelDescription, path: Path) -> float | None:
    experiment = description.defaultExperiment
    text = experiment.tolerance if experiment is not None else None
    if text is None:
        return None
    try:
        tolerance = float(text)
    except ValueError:
        tolerance = math.nan
    if not (math.isfinite(tolerance) and tolerance > 0):
        raise FMUFileError(f"{path}: DefaultExperiment tolerance {text!r} is not a positive "
                           "number")
    return tolerance


def _interfaces(description: ModelDescription, path: Path) -> dict[str, FMUInterface]:
    """The interfaces the FMU declares; none at all is an error."""
    interfaces = {}
    fmi3 = str(description.fmiVersion).startswith("3.")
    # input and output derivatives reach the engine through FMI 2.0's and 3.0's back-ends only
    derivatives = fmi3 or str(description.fmiVersion).startswith("2.")
    for name, element, part in (("co-simulation", "CoSimulation", description.coSimulation),
                                ("model-exchange", "ModelExchange", description.modelExchange)):
        if part is None:
            continue
        cosimulation = element == "CoSimulation"
        moving: tuple[int, ...] = ()
        if cosimulation and fmi3 and getattr(part, "providesIntermediateUpdate", False):
            from .description_fmi3 import intermediate_inputs

            moving = tuple(intermediate_inputs(path))
        interpolates = bool(moving) if fmi3 else derivatives and cosimulation and \
            bool(getattr(part, "canInterpolateInputs", False))
        interfaces[name] = FMUInterface(
            name, _model_identifier(part.modelIdentifier, path, element),
            bool(part.canGetAndSetFMUstate), bool(part.providesDirectionalDerivative),
            bool(part.canBeInstantiatedOnlyOncePerProcess), interpolates,
            int(getattr(part, "maxOutputDerivativeOrder", 0) or 0)
            if cosimulation and derivatives else 0,
            moving)
    if not interfaces:
        raise FMUFileError(f"{path}: the modelDescription declares neither CoSimulation nor "
                           "ModelExchange")
    return interfaces


def _model_identifier(identifier: str | None, path: Path, element: str) -> str:
    """The modelIdentifier, which names the binary: a file name, never a path."""
    if not identifier:
        raise FMUFileError(f"{path}: the {element} element has no modelIdentifier")
    if any(c in identifier for c in "/\\\0") or ".." in identifier:
        raise FMUFileError(f"{path}: modelIdentifier {identifier!r} is not a file name (it "
                           "contains a path separator, '..' or a NUL); refused")
    return identifier


_INPUT_DEFAULTS = {PortType.REAL: 0.0, PortType.INT: 0, PortType.BOOL: False}


class _Parts:
    """What the port maps of an FMU are made of, in document order: (name, value) pairs of
    scalars, Blocks of arrays."""

    def __init__(self) -> None:
        self.input_specs: list[tuple[str, Any] | Block] = []
        self.output_specs: list[tuple[str, Any] | Block] = []
        self.parameters: list[tuple[str, Any] | Block] = []
        self.input_starts: list[tuple[str, Any] | Block] = []
        self.value_references: list[tuple[str, Any] | Block] = []

    def store(self, info: FMUInfo, with_arrays: bool) -> None:
        for name, parts in vars(self).items():  # without arrays, a dict's speed
            setattr(info, name, ElementMap.in_order(parts) if with_arrays
                    else ElementMap(dict(parts)))  # type: ignore[arg-type]


def _collect_ports_and_parameters(info: FMUInfo, ports: list[Any]) -> None:
    """Ports, parameters, input starts and value references of the `ports` (ScalarVariables
    and FMI 3.0 ArrayPorts)."""
    unreadable: dict[str, list[str]] = {}  # unit pint cannot read -> the variables using it
    readable: dict[str, str | None] = {}  # the FMI unit -> what pint reads (a large FMU
    parts = _Parts()  # repeats a few units many times)
    defined: dict[str, str] | None = None  # the units the FMU defines, read when needed
    ambiguous = info.ambiguous_names
    for port in ports:
        variable = port.variable if isinstance(port, ArrayPort) else port
        if ambiguous and variable.name in ambiguous:
            continue
        kind = PORT_TYPES.get(variable.type)
        if kind is None:
            if variable.type in info.standard.text_types:
                parts.value_references.append((variable.name, variable.valueReference))
                _collect_text(info, variable, parts)
            continue
        unit = variable_unit(variable) if kind == PortType.REAL else None
        if unit:
            if unit not in readable:
                readable[unit] = _pint_unit(unit)
                if readable[unit] is None:  # then the FMU's own definition, if it has one
                    defined = unit_definitions(info.path) if defined is None else defined
                    readable[unit] = defined.get(unit)
            if readable[unit] is None:
                unreadable.setdefault(unit, []).append(variable.name)
            unit = readable[unit]
        if isinstance(port, ArrayPort):
            _collect_array(parts, port, kind, unit)
            continue
        parts.value_references.append((variable.name, variable.valueReference))
        if variable.causality in ("input", "output"):
            spec = PortSpec(variable.name, kind, "in" if variable.causality == "input" else "out",
                            unit, variable.description)
            (parts.input_specs if spec.direction == "in" else parts.output_specs).append(
                (variable.name, spec))
            if spec.direction == "in":
                start = _start_value(variable, kind)
                parts.input_starts.append(
                    (variable.name, _INPUT_DEFAULTS[kind] if start is None else start))
        elif variable.causality == "parameter":
            parts.parameters.append((variable.name, Parameter(
                variable.name, variable.valueReference, kind, unit,
                variable.variability == "tunable", _start_value(variable, kind), variable.type)))
    parts.store(info, with_arrays=any(isinstance(port, ArrayPort) for port in ports))
    for unit, names in unreadable.items():
        others = f" and {len(names) - 1} more" if len(names) > 1 else ""
        logger.warning("%s: unit %r of variable %r%s is unknown to pint; dropped (those ports "
                       "carry no unit)", info.path.name, unit, names[0], others)


_PYTHON_TYPES = {PortType.REAL: float, PortType.INT: int, PortType.BOOL: bool}


def _collect_array(parts: _Parts, array: ArrayPort, kind: PortType, unit: str | None) -> None:
    """An array port's Blocks: its elements' objects are made when asked for."""
    variable = array.variable
    typed = _PYTHON_TYPES[kind]

    def start(position: int) -> Any:
        value = array.start(position)
        return None if value is None else typed(value)

    def block(make: Any) -> Block:
        return Block(array.name, array.shape, make)

    parts.value_references.append(block(lambda position, name: array.first_vr + position))
    if variable.causality == "parameter":
        tunable = variable.variability == "tunable"
        parts.parameters.append(block(lambda position, name: Parameter(
            name, array.first_vr + position, kind, unit, tunable, start(position),
            variable.type)))
        return
    direction = "in" if variable.causality == "input" else "out"
    spec = block(lambda position, name: PortSpec(name, kind, direction, unit,
                                                 variable.description))
    (parts.input_specs if direction == "in" else parts.output_specs).append(spec)
    if direction == "in":
        default = _INPUT_DEFAULTS[kind]
        parts.input_starts.append(block(lambda position, name: default
                                        if array.starts is None else start(position)))


def _collect_text(info: FMUInfo, variable: ScalarVariable, parts: _Parts) -> None:
    """A String (any FMI version) or Binary (FMI 3.0) variable. An input or output is a port
    (its values are texts or bytes); a parameter or an input is set like a parameter."""
    binary = variable.type == "Binary"
    start: str | bytes | None = variable.start
    if binary and start is not None:
        start = bytes.fromhex(start.strip())
    if variable.causality in ("input", "output"):
        direction = "in" if variable.causality == "input" else "out"
        spec = PortSpec(variable.name, PortType.BINARY if binary else PortType.STRING,
                        direction, None, variable.description)
        (parts.input_specs if direction == "in" else parts.output_specs).append(
            (variable.name, spec))
        if direction == "in":
            parts.input_starts.append((variable.name, start or (b"" if binary else "")))
    if variable.causality == "output":
        return
    parts.parameters.append((variable.name, Parameter(
        variable.name, variable.valueReference, PortType.STRING, None,
        variable.causality == "input" or variable.variability == "tunable", start,
        variable.type)))


def _collect_feedthrough(info: FMUInfo, ports: list[Any], outputs: list[Any]) -> None:
    """Output -> the inputs it depends on directly, from ModelStructure's `outputs`. Read per
    variable (an FMI 3.0 array as a whole); an output's set names each element of the input
    arrays it depends on, made when asked for."""
    from fmpy.model_description import ModelDescription

    variables = [p.variable if isinstance(p, ArrayPort) else p for p in ports]
    # The analysis reads inputs, outputs and ModelStructure: hand it those, not every local.
    ports_only = ModelDescription()
    ports_only.modelVariables = [v for v in variables if v.causality in ("input", "output")]
    ports_only.outputs = outputs
    declared = feedthrough_from_model_description(ports_only)
    info.undeclared_outputs = undeclared_outputs(ports_only)
    arrays = {p.name: p for p in ports if isinstance(p, ArrayPort)}
    inputs = {v.name for v in ports_only.modelVariables if v.causality == "input" and
              (v.name in arrays or v.name in info.input_specs)}

    def elements(names: set[str]) -> set[str]:
        found = set()
        for name in names:
            array = arrays.get(name)
            found.update([name] if array is None else
                         Block(name, array.shape, array.element).names())
        return found

    parts: list[tuple[str, Any] | Block] = []
    for port in ports:
        name = port.name
        if name not in declared or not (name in arrays or name in info.output_specs):
            continue  # not an output, or one no port carries (String, Binary)
        dependencies = declared[name] & inputs
        if not dependencies.isdisjoint(arrays) or name in arrays:
            shape = arrays[name].shape if name in arrays else ()
            parts.append(Block(name, shape, lambda position, element, d=dependencies:
                               elements(d)))
        else:
            parts.append((name, dependencies))
    info.feedthrough = ElementMap.in_order(parts)
