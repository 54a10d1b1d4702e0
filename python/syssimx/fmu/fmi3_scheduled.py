"""An FMI 3.0 Scheduled Execution instance: the FMU's binary called through cffi.

The engine's FMI 3.0 back-end instantiates Co-Simulation and Model Exchange only; a Scheduled
Execution FMU is run by the Python scheduler of ScheduledExecutionComponent, through this
module, which is the one place its fmi3 functions are called. Every call's status is checked:
fmi3Warning is logged, anything worse raises SimulationError naming the function.

The FMU's callbacks: log messages go to the "syssimx.fmu" logger; clockUpdate (the FMU's
intermediate update: an output clock ticked or a countdown clock's interval became known) calls
the `on_clock_update` the instance was made with; lockPreemption/unlockPreemption are counted
and must pair. syssimx activates one partition at a time on the calling thread, so there is no
other partition to hold off: the lock only has to be balanced.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import cffi

from ..errors import SimulationError

logger = logging.getLogger("syssimx.fmu")

_DECLARATIONS = """
typedef void *fmi3Instance;
typedef void (*fmi3LogMessageCallback)(void *, int, const char *, const char *);
typedef void (*fmi3ClockUpdateCallback)(void *);
typedef void (*fmi3LockPreemptionCallback)(void);
typedef void (*fmi3UnlockPreemptionCallback)(void);
fmi3Instance fmi3InstantiateScheduledExecution(const char *, const char *, const char *, bool,
    bool, void *, fmi3LogMessageCallback, fmi3ClockUpdateCallback,
    fmi3LockPreemptionCallback, fmi3UnlockPreemptionCallback);
int fmi3EnterInitializationMode(fmi3Instance, bool, double, double, bool, double);
int fmi3ExitInitializationMode(fmi3Instance);
int fmi3ActivateModelPartition(fmi3Instance, uint32_t, double);
int fmi3GetClock(fmi3Instance, const uint32_t *, size_t, bool *);
int fmi3GetIntervalDecimal(fmi3Instance, const uint32_t *, size_t, double *, int *);
int fmi3Terminate(fmi3Instance);
void fmi3FreeInstance(fmi3Instance);
"""
# FMI 3.0 value types -> the C type of their fmi3Get<Type>/fmi3Set<Type> arrays
C_TYPES = {"Float64": "double", "Float32": "float", "Int8": "int8_t", "UInt8": "uint8_t",
           "Int16": "int16_t", "UInt16": "uint16_t", "Int32": "int32_t", "UInt32": "uint32_t",
           "Int64": "int64_t", "UInt64": "uint64_t", "Boolean": "bool", "Enumeration": "int64_t"}
_ACCESSORS = "".join(
    f"int fmi3Get{name}(fmi3Instance, const uint32_t *, size_t, {c_type} *, size_t);\n"
    f"int fmi3Set{name}(fmi3Instance, const uint32_t *, size_t, const {c_type} *, size_t);\n"
    for name, c_type in C_TYPES.items() if name != "Enumeration")
_STATUS = ("OK", "Warning", "Discard", "Error", "Fatal")
# fmi3IntervalQualifier
INTERVAL_NOT_YET_KNOWN, INTERVAL_UNCHANGED, INTERVAL_CHANGED = 0, 1, 2

_ffi = cffi.FFI()
_ffi.cdef(_DECLARATIONS + _ACCESSORS)


class ScheduledInstance:
    """One instance of a Scheduled Execution FMU, in Clock Activation Mode once initialized."""

    def __init__(self, binary: Path, name: str, token: str, resources: Path | None,
                 on_clock_update: Callable[[], None]) -> None:
        self.name = name
        self._library: Any = _ffi.dlopen(str(binary))
        # looked up now: free() may run from a finalizer during a lookup in the same library,
        # whose lock is not reentrant (the lookup would wait for itself)
        self._terminate = self._library.fmi3Terminate
        self._free_instance = self._library.fmi3FreeInstance
        self._on_clock_update = on_clock_update
        self.preemption_depth = 0
        self.callback_error: BaseException | None = None

        @_ffi.callback("void(void *, int, const char *, const char *)")
        def log_message(_env: Any, status: int, category: Any, message: Any) -> None:
            level = logging.INFO if status == 0 else logging.WARNING
            logger.log(level, "%s [%s]: %s", name, _ffi.string(category).decode(errors="replace")
                       if category else "", _ffi.string(message).decode(errors="replace"))

        @_ffi.callback("void(void *)")
        def clock_update(_env: Any) -> None:
            try:
                self._on_clock_update()
            except BaseException as exc:  # raised once the FMU's call returns
                self.callback_error = self.callback_error or exc

        @_ffi.callback("void(void)")
        def lock_preemption() -> None:
            self.preemption_depth += 1

        @_ffi.callback("void(void)")
        def unlock_preemption() -> None:
            self.preemption_depth -= 1
            if self.preemption_depth < 0 and self.callback_error is None:
                self.callback_error = SimulationError(
                    f"{name}: the FMU unlocked preemption it had not locked")

        self._callbacks = (log_message, clock_update, lock_preemption, unlock_preemption)
        location = None if resources is None else _ffi.new("char[]", resources.as_uri()
                                                           .encode() + b"/")
        self._instance = self._library.fmi3InstantiateScheduledExecution(
            name.encode(), token.encode(), location if location is not None else _ffi.NULL,
            False, False, _ffi.NULL, *self._callbacks)
        if self._instance == _ffi.NULL:
            raise SimulationError(f"{name}: fmi3InstantiateScheduledExecution failed")

    def initialize(self, start_time: float) -> None:
        """Initialization Mode at start_time and out of it, into Clock Activation Mode."""
        self._check("fmi3EnterInitializationMode", self._library.fmi3EnterInitializationMode(
            self._instance, False, 0.0, start_time, False, 0.0))
        self._check("fmi3ExitInitializationMode",
                    self._library.fmi3ExitInitializationMode(self._instance))

    def activate(self, clock: int, time: float) -> None:
        """Run the model partition of input clock `clock` at `time`."""
        self._check("fmi3ActivateModelPartition",
                    self._library.fmi3ActivateModelPartition(self._instance, clock, time))
        if self.preemption_depth > 0 and self.callback_error is None:
            self.callback_error = SimulationError(
                f"{self.name}: the partition of clock {clock} returned with preemption locked")
        if self.callback_error is not None:
            error, self.callback_error = self.callback_error, None
            raise error

    def clocks(self, references: Sequence[int]) -> list[bool]:
        """fmi3GetClock: whether each output clock ticked."""
        values = _ffi.new("bool[]", len(references))
        self._check("fmi3GetClock", self._library.fmi3GetClock(
            self._instance, list(references), len(references), values))
        return list(values)

    def intervals(self, references: Sequence[int]) -> list[tuple[float, int]]:
        """fmi3GetIntervalDecimal: (interval, qualifier) of each clock."""
        intervals = _ffi.new("double[]", len(references))
        qualifiers = _ffi.new("int[]", len(references))
        self._check("fmi3GetIntervalDecimal", self._library.fmi3GetIntervalDecimal(
            self._instance, list(references), len(references), intervals, qualifiers))
        return list(zip(intervals, qualifiers, strict=True))

    def get(self, fmi_type: str, references: Sequence[int]) -> list[Any]:
        """The values of the variables `references`, all of type `fmi_type` (Float64, ...)."""
        values = _ffi.new(f"{C_TYPES[fmi_type]}[]", len(references))
        function = f"fmi3Get{_accessor(fmi_type)}"
        self._check(function, getattr(self._library, function)(
            self._instance, list(references), len(references), values, len(references)))
        return list(values)

    def set(self, fmi_type: str, references: Sequence[int], values: Sequence[Any]) -> None:
        function = f"fmi3Set{_accessor(fmi_type)}"
        array = _ffi.new(f"{C_TYPES[fmi_type]}[]", list(values))
        self._check(function, getattr(self._library, function)(
            self._instance, list(references), len(references), array, len(references)))

    def free(self) -> None:
        """fmi3Terminate and fmi3FreeInstance; the instance is unusable after."""
        if self._instance == _ffi.NULL:
            return
        instance, self._instance = self._instance, _ffi.NULL
        status = self._terminate(instance)
        self._free_instance(instance)
        self._check("fmi3Terminate", status)

    def _check(self, function: str, status: int) -> None:
        if status == 1:
            logger.warning("%s: %s returned fmi3Warning", self.name, function)
        elif status != 0:
            word = _STATUS[status] if 0 <= status < len(_STATUS) else str(status)
            raise SimulationError(f"{self.name}: {function} returned fmi3{word}")


def _accessor(fmi_type: str) -> str:
    return "Int64" if fmi_type == "Enumeration" else fmi_type
