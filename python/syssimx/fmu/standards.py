"""The FMI standards syssimx runs: one object per version, with the same methods.

The version is decided once, where the archive's modelDescription is read (description.py
picks the standard); everything after asks the FMU's standard (`FMUInfo.standard`) instead of
comparing version strings: where its binaries lie, how its variables become ports, what its
binary is given at instantiation, what the engine needs to load it.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple, Protocol

from ..engine import ffi, lib
from . import description_fmi1, description_fmi2, description_fmi3

if TYPE_CHECKING:
    from fmpy.model_description import ModelDescription


class FMUInfo(Protocol):
    """What a standard reads of an FMU's info (info.FMUInfo, which builds on this module)."""

    description: Any
    fmi3_variables: Any


class FMUInterface(Protocol):
    """What a standard reads of one of the FMU's interfaces (info.FMUInterface)."""

    name: str
    model_identifier: str

_LINUX = sys.platform.startswith("linux")
PORT_CAUSALITIES = ("input", "output", "parameter")  # locals are no ports


class Variables(NamedTuple):
    """A description's variables as syssimx uses them: every one (`all`), by name, the
    inputs, outputs and parameters (`ports`; FMI 3.0: an array port as one ArrayPort), the
    ModelStructure outputs with their dependencies, and FMI 3.0's type table and structural
    parameters (empty otherwise)."""

    all: Iterable[Any]
    by_name: Mapping[str, Any]
    ports: list[Any]
    outputs: list[Any]
    engine_table: description_fmi3.EngineTable
    structural: dict[str, list[str]]


class Standard:
    """FMI 2.0 (the others differ where they override)."""

    version = "2.0"
    engine_version = 2  # ssx_fmi_version
    function_prefix = "fmi2"  # of the standard's function names
    platform = "linux64" if _LINUX else sys.platform
    isolatable = True  # the FMU host process speaks it
    has_fmu_state = True  # get/set FMU state exists (whether an FMU has it, it declares)
    # value types the engine's float64 ports do not carry: set and read as texts
    text_types: tuple[str, ...] = ("String",)

    @property
    def name(self) -> str:
        return f"FMI {self.version}"

    def declared_by(self, version: str) -> bool:
        """Whether a description declaring fmiVersion `version` is of this standard."""
        return version == self.version

    def describe(self, md: Any, path: Path, text: bytes | bytearray) -> ModelDescription:
        """The description of what the engine's reader read into `md` from `text` (the UTF-8
        modelDescription of the archive at `path`); FMUFileError naming the file when it is
        unusable."""
        from ..errors import FMUFileError

        problem = description_fmi2.problem_message(md, path)
        if problem is not None:
            raise FMUFileError(problem)
        return self._described(md, path, text)

    def _described(self, md: Any, path: Path, text: bytes | bytearray) -> ModelDescription:
        return description_fmi2.describe(md, path)

    def variables(self, description: ModelDescription, path: Path) -> Variables:
        table = description.modelVariables
        return Variables(table, table.by_name(), table.with_causality(*PORT_CAUSALITIES),
                         description.outputs, description_fmi3.EngineTable([], []), {})

    def binary_name(self, model_identifier: str) -> str:
        return f"binaries/{self.platform}/{model_identifier}.so"

    def resource_location(self, unzip_dir: Path) -> str:
        """What the binary is given at instantiation to find its files."""
        return (unzip_dir / "resources").as_uri()

    def engine_variables(self, info: FMUInfo, interface: FMUInterface) -> tuple[Any, Any]:
        """The ssx_fmi3_variables of the load spec (NULL where the standard has none) and
        what it points at."""
        return ffi.NULL, None

    def load_spec(self, info: FMUInfo, interface: FMUInterface, binary: Path,
                  unzip_dir: Path, instance_name: str, host: Path | None,
                  step_timeout: float | None) -> tuple[Any, list[Any]]:
        """The engine's ssx_fmu_load_spec, and what it points at (keep it alive until the
        engine copied it)."""
        engine = lib()
        texts = [ffi.new("char[]", text.encode()) for text in (
            str(binary), interface.model_identifier, info.description.guid or "",
            self.resource_location(unzip_dir), instance_name)]
        host_text = ffi.new("char[]", str(host).encode()) if host is not None else ffi.NULL
        variables, pointed_at = self.engine_variables(info, interface)
        spec = ffi.new("ssx_fmu_load_spec *", {
            "version": self.engine_version,
            "interface": engine.SSX_MODEL_EXCHANGE if interface.name == "model-exchange"
            else engine.SSX_CO_SIMULATION,
            "binary_path": texts[0], "model_identifier": texts[1], "guid": texts[2],
            "resource_location": texts[3], "instance_name": texts[4], "logging_on": 0,
            "host_path": host_text, "step_timeout": step_timeout or 0.0,
            "fmi3_variables": variables})
        return spec, [texts, host_text, variables, pointed_at]


class FMI1(Standard):
    """FMI 1.0: its own function names (no "fmi2"-like prefix), no FMU state, and one
    interface per FMU."""

    version = "1.0"
    engine_version = 1
    function_prefix = "fmi"
    has_fmu_state = False

    def _described(self, md: Any, path: Path, text: bytes | bytearray) -> ModelDescription:
        return description_fmi1.describe_fmi1(md, path, text)

    def resource_location(self, unzip_dir: Path) -> str:
        """FMI 1.0 Co-Simulation gives the slave the URI of the extracted archive
        (fmuLocation); Model Exchange passes nothing."""
        return unzip_dir.as_uri()


class FMI3(Standard):
    version = "3.0"
    engine_version = 3
    function_prefix = "fmi3"
    # FMI 3.0 names the platform by architecture and system
    platform = "x86_64-linux" if _LINUX else sys.platform
    isolatable = False
    text_types = ("String", "Binary")

    def declared_by(self, version: str) -> bool:
        return version.startswith("3.")  # its release candidates too

    def describe(self, md: Any, path: Path, text: bytes | bytearray) -> ModelDescription:
        """FMPy reads FMI 3.0 (the engine's reader stopped at the root element)."""
        return description_fmi3.read_fmi3_description(path)

    def variables(self, description: ModelDescription, path: Path) -> Variables:
        from ..core.element_map import Block, ElementMap
        from .fmi3_arrays import ArrayPort, ElementsInPlace, array_variables

        found = array_variables(description, path)
        in_order = found.in_order
        by_name = ElementMap.in_order([Block(v.name, v.shape, v.element)
                                       if isinstance(v, ArrayPort) else (v.name, v)
                                       for v in in_order])
        return Variables(ElementsInPlace(in_order), by_name,
                         [v for v in in_order if v.causality in PORT_CAUSALITIES],
                         description.outputs, description_fmi3.engine_table(in_order),
                         found.structural)

    def resource_location(self, unzip_dir: Path) -> str:
        """FMI 3.0 gives the resources as a directory path ending in a separator."""
        return f"{unzip_dir / 'resources'}/"

    def engine_variables(self, info: FMUInfo, interface: FMUInterface) -> tuple[Any, Any]:
        """The FMU's type table. Co-Simulation: event mode when the FMU has it, early return
        when it may return early: its events are then handled at their time."""
        return description_fmi3.engine_variables(
            info.fmi3_variables, info.description.coSimulation,
            model_exchange=interface.name == "model-exchange",
            intermediate=interface.intermediate_inputs,
            clocks=description_fmi3.ticked_clocks(info.clocks, interface.name, info.path,
                                                  info.description.coSimulation))


STANDARDS: tuple[Standard, ...] = (FMI1(), Standard(), FMI3())


def standard_of(version: str | None) -> Standard | None:
    """The standard of an fmiVersion ("2.0", "3.0", ...); None for one syssimx does not run."""
    return next((s for s in STANDARDS if version is not None and s.declared_by(version)), None)


def supported() -> str:
    """The standards syssimx runs, for messages."""
    names = [s.name for s in STANDARDS]
    return f"{', '.join(names[:-1])} and {names[-1]} Co-Simulation and Model Exchange FMUs"
