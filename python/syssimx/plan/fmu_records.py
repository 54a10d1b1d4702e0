"""The records of an FMU component: how its binary is loaded (its `fmu` or `model_exchange`
record, `isolated`, and an FMI 3.0 FMU's type table), as Python loaded it."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..engine import ffi
from .records import PlanRecords, Word

# the words of ssx_fmi3_type, in the order of the engine's enum
FMI3_TYPES = ("float64", "float32", "int8", "uint8", "int16", "uint16", "int32", "uint32",
              "int64", "uint64", "boolean")


@dataclass(frozen=True)
class FMULoad:
    """What loading an FMU's binary takes: its standard (1, 2 or 3), its unpacked folder, the
    interface's model identifier, the guid (FMI 3.0: instantiation token), the instance name;
    an FMI 3.0 FMU's type table (the load spec's ssx_fmi3_variables, NULL for none) and, for an
    FMU loaded into a host process of its own, the step timeout (0: none)."""

    version: int
    folder: str
    model_identifier: str
    token: str
    instance_name: str
    fmi3_variables: Any = None
    isolated: bool = False
    step_timeout: float = 0.0


@dataclass(frozen=True)
class ScheduledClock:
    """A clock of a Scheduled Execution component as the engine takes it (its
    scheduled_clock record): `kind` an ssx_scheduled_clock_kind (0 periodic, 1 triggered,
    2 countdown, 3 output), `priority` -1 for none, `interval` NaN for the FMU's, `times` a
    triggered clock's, `moves` the outputs each tick reads."""

    kind: int
    value_reference: int
    priority: int
    interval: float
    shift: float
    interval_tunable: bool
    times: tuple[float, ...] = ()
    moves: tuple[str, ...] = ()


def write_fmu(records: PlanRecords, index: int, name: str, can_get_set_state: bool,
              model_exchange: tuple[int, int] | None, load: FMULoad) -> None:
    """The records that load and add FMU component `index`; model_exchange: (continuous
    states, event indicators) of an FMU the engine integrates."""
    where = (load.version, load.folder, load.model_identifier, load.token, load.instance_name,
             False)
    if model_exchange is None:
        records.add("fmu", name, can_get_set_state, *where, about=name)
    else:
        records.add("model_exchange", name, can_get_set_state, *model_exchange, *where,
                    about=name)
    if load.isolated:
        records.add("isolated", index, float(load.step_timeout), about=name)
    table = load.fmi3_variables
    if table is not None and table != ffi.NULL:
        _write_fmi3_table(records, index, name, table)


def write_scheduled(records: PlanRecords, index: int, name: str, load: FMULoad) -> None:
    """The records that load and add Scheduled Execution component `index` (an FMI 3.0 FMU
    whose type table lists its ports, output clocks and countdown clocks)."""
    records.add("scheduled_execution", name, load.folder, load.model_identifier, load.token,
                load.instance_name, False, about=name)
    _write_fmi3_table(records, index, name, load.fmi3_variables)


def _write_fmi3_table(records: PlanRecords, index: int, name: str, table: Any) -> None:
    """An FMI 3.0 FMU's type table (an ssx_fmi3_variables) as its records."""
    records.add("fmi3_variables", index, bool(table.event_mode_used),
                bool(table.early_return_allowed), about=name)
    arrays = table.size != ffi.NULL
    for k in range(table.n):
        kind = Word(FMI3_TYPES[table.type[k]])
        variable = ffi.string(table.name[k]).decode()
        if arrays and table.size[k] != 0:
            records.add("fmi3_element", index, int(table.vr[k]), kind, variable,
                        int(table.fmu_vr[k]), int(table.element[k]), int(table.size[k]),
                        float(table.start[k]), about=f"{name}.{variable}")
        else:
            records.add("fmi3_variable", index, int(table.vr[k]), kind, variable,
                        about=f"{name}.{variable}")
    for k in range(table.n_intermediate):
        records.add("fmi3_intermediate", index, int(table.intermediate_vr[k]), about=name)
    for k in range(table.n_clocks):
        records.add("fmi3_clock", index, int(table.clock_vr[k]), float(table.clock_period[k]),
                    float(table.clock_shift[k]), about=name)
    for k in range(table.n_triggered_clocks):
        records.add("fmi3_triggered_clock", index, int(table.triggered_clock_vr[k]), about=name)
    for k in range(table.n_output_clocks):
        records.add("fmi3_output_clock", index, int(table.output_clock_vr[k]), about=name)
    repeats = table.countdown_clock_repeats
    for k in range(table.n_countdown_clocks):
        kind = "fmi3_changing_clock" if repeats != ffi.NULL and repeats[k] else \
            "fmi3_countdown_clock"
        records.add(kind, index, int(table.countdown_clock_vr[k]), about=name)
