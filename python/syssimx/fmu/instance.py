"""FMUInstance: FMPy's FMU2Slave method names over the engine-owned FMU instance.

The engine owns the fmi2 instance (it steps it without Python); this proxy lets user code
(the seed's FMUComponent subclass, event handlers) drive the same instance. A status above
Warning raises FMUError with the FMU's last log message. Once the FMU is released
(FMUComponent.free()), every call raises FMUError instead of touching freed memory.

Finalizers run whenever the garbage collector runs, possibly while cffi holds the lock that a
first lookup of a library function takes: they only call functions resolved beforehand.
"""

from __future__ import annotations

import weakref
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from ..core.port import PortType
from ..engine import ffi, lib, status_name, string
from ..errors import FMUError

# values to write by type: value references and as many values
Values = Mapping[PortType, tuple[Sequence[int], Sequence[Any]]]


class FMUState:
    """An FMU state taken with getFMUstate. Freed by freeFMUstate or when garbage collected;
    a state of an instance that has since been freed or replaced was released with it."""

    def __init__(self, instance: FMUInstance, handle: Any) -> None:
        self._instance = instance
        self.generation = instance.generation
        self.handle = handle  # void ** holding the fmi2FMUstate
        self._finalizer = weakref.finalize(self, _free_state, instance._free_state_function,
                                           instance, self.generation, handle)

    def free(self) -> None:
        self._finalizer()


def _free_state(free_state: Any, instance: FMUInstance, generation: int, handle: Any) -> None:
    if handle[0] != ffi.NULL and instance.generation == generation and instance.alive():
        free_state(instance.fmu, handle)


class FMUInstance:
    """Proxy with FMU2Slave's methods; `mode` is "none", "instantiated", "init" or "step"."""

    def __init__(self, fmu: Any, component_name: str, function_prefix: str = "fmi2") -> None:
        self._fmu = fmu
        self.component_name = component_name
        self._function_prefix = function_prefix  # of the FMU's standard: "fmi2", "fmi3", ...
        self.mode = "none"
        # resolved and allocated now: finalizers read the generation
        self._free_state_function = lib().ssx_fmu_free_state
        self._get_counters = lib().ssx_fmu_get_counters
        self._counters = ffi.new("ssx_fmu_counters *")
        # initialize's experiment, filled at each call (the engine reads it before anything
        # that could call initialize again)
        self._experiment = ffi.new("ssx_fmu_experiment *")
        # start values by the variables they write: see _start_values
        self._kept_starts: dict[tuple[Any, ...], tuple[Any, list[Any]]] = {}

    @property
    def generation(self) -> int:
        """The instantiations so far (a reset keeps the instance, so its FMU states stay
        valid); -1 once the FMU is released."""
        if self._fmu is None:
            return -1
        self._get_counters(self._fmu, self._counters)
        return int(self._counters.instantiate)

    @property
    def fmu(self) -> Any:
        """The engine's ssx_fmu; FMUError once released."""
        if self._fmu is None:
            raise FMUError(f"{self.component_name}: the FMU was released by "
                           "FMUComponent.free(); create a new FMUComponent to use it again",
                           component=self.component_name)
        return self._fmu

    def released(self) -> bool:
        return self._fmu is None

    def release(self, free_fmu: Any) -> None:
        """Free the instance and unload the binary with `free_fmu` (ssx_fmu_free, resolved
        by the caller beforehand); afterwards every call raises FMUError."""
        if self._fmu is None:
            return
        self.mode = "none"
        fmu, self._fmu = self._fmu, None
        free_fmu(fmu)

    def alive(self) -> bool:
        return self.mode != "none"

    def counters(self) -> dict[str, int]:
        """fmi2 calls made on this FMU so far (by the engine and through this proxy)."""
        raw = ffi.new("ssx_fmu_counters *")
        lib().ssx_fmu_get_counters(self.fmu, raw)
        return {name: int(getattr(raw, name)) for name in
                ("do_step", "get_state", "set_state", "get_values", "set_values", "instantiate",
                 "directional_derivative", "reset")}

    def _check(self, status: int, call: str) -> int:
        if status > 1 or status < 0:
            # the engine names the call by the FMU's standard ("fmi3GetFloat64", ...); a call
            # outside the FMU's interface has no name there: this proxy's, in the standard's
            named = string(lib().ssx_fmu_last_call(self.fmu))
            call = named if named.startswith(self._function_prefix) \
                else call.replace("fmi2", self._function_prefix, 1)
            message = string(lib().ssx_fmu_last_message(self.fmu))
            raise FMUError(f"{self.component_name}: {call} returned {status_name(status)}"
                           + (f": {message}" if message else ""),
                           component=self.component_name, status=status, fmu_message=message)
        return status

    # ------------------------------------------------------------ life cycle
    def initialize(self, start_time: float, tolerance: float | None = None,
                   starts: Values | None = None,
                   in_initialization_mode: Callable[[], None] | None = None,
                   system_exits: bool = False) -> None:
        """An instance ready to step, in one engine call: reset (a live instance) or
        instantiate, setupExperiment,
        enterInitializationMode, write `starts`, call `in_initialization_mode` (it may write
        more through this proxy; what it raises is raised here), exitInitializationMode.
        system_exits: all but the exit, which the system's initialize (ssx_initialize) makes
        right after, with the connected inputs given; the proxy counts the instance as
        stepping from here on."""
        self.mode = "init"  # what the FMU is in while in_initialization_mode runs
        experiment = self._experiment
        experiment.start_time = start_time
        experiment.tolerance_defined = tolerance is not None
        experiment.tolerance = tolerance or 0.0
        values = self._start_values(starts) if starts else ffi.NULL
        raised: list[BaseException] = []

        def during(_user: Any) -> int:
            try:
                in_initialization_mode()  # type: ignore[misc]
            except BaseException as exc:  # raised below, an interrupt too
                raised.append(exc)
                return -1
            return 0

        callback = ffi.NULL if in_initialization_mode is None \
            else ffi.callback("int(void *)", during)
        fmu = self._fmu if self._fmu is not None else self.fmu  # (FMUError once released)
        initialize = lib().ssx_fmu_enter_initialization if system_exits \
            else lib().ssx_fmu_initialize
        status = initialize(fmu, experiment, values, callback, ffi.NULL)
        if status in (0, 1):
            self.mode = "step"
            return
        self.mode = "init" if lib().ssx_fmu_is_instantiated(self.fmu) else "none"
        if raised:
            raise raised[0]
        self._check(status, string(lib().ssx_fmu_last_call(self.fmu)))

    def _start_values(self, starts: Values) -> Any:
        """The ssx_fmu_values of `starts` in C arrays kept for the next call that writes the
        same variables (a loop of members writes the same parameters each time): then only
        the values are written into them. The engine reads them during the call only."""
        layout = tuple((kind, *refs) for kind, (refs, _) in starts.items())
        kept = self._kept_starts.get(layout)
        if kept is None:
            if len(self._kept_starts) == _KEPT_LAYOUTS:
                self._kept_starts.clear()
            kept = self._kept_starts[layout] = start_values(starts)
            return kept[0]
        values, arrays = kept
        for (kind, (_, vals)), array in zip(starts.items(), arrays[2::2], strict=True):
            convert = _VALUES_LAYOUT[kind][4]
            array[0:len(vals)] = [convert(v) for v in vals]
        return values

    def instantiate(self, visible: bool = False, callbacks: Any = None,
                    loggingOn: bool = False) -> None:  # noqa: N803 (FMPy's names)
        self.mode = "none"
        self._check(lib().ssx_fmu_instantiate(self.fmu), "fmi2Instantiate")
        self.mode = "instantiated"

    def setupExperiment(self, tolerance: float | None = None, startTime: float = 0.0,  # noqa: N802,N803
                        stopTime: float | None = None) -> None:  # noqa: N803
        self._check(lib().ssx_fmu_setup_experiment(
            self.fmu, tolerance is not None, tolerance or 0.0, startTime, stopTime is not None,
            stopTime or 0.0), "fmi2SetupExperiment")

    def enterInitializationMode(self) -> None:  # noqa: N802
        self._check(lib().ssx_fmu_enter_initialization_mode(self.fmu),
                    "fmi2EnterInitializationMode")
        self.mode = "init"

    def exitInitializationMode(self) -> None:  # noqa: N802
        self._check(lib().ssx_fmu_exit_initialization_mode(self.fmu),
                    "fmi2ExitInitializationMode")
        self.mode = "step"

    def doStep(self, currentCommunicationPoint: float, communicationStepSize: float,  # noqa: N802,N803
               noSetFMUStatePriorToCurrentPoint: bool = True) -> int:  # noqa: N803
        if not communicationStepSize > 0.0:
            raise ValueError(f"{self.component_name}: doStep needs a positive step, "
                             f"got {communicationStepSize}")
        return self._check(lib().ssx_fmu_do_step(
            self.fmu, currentCommunicationPoint, communicationStepSize,
            int(bool(noSetFMUStatePriorToCurrentPoint))), "fmi2DoStep")

    def reset(self) -> None:
        self._check(lib().ssx_fmu_reset(self.fmu), "fmi2Reset")
        self.mode = "instantiated"

    def terminate(self) -> None:
        self._check(lib().ssx_fmu_terminate(self.fmu), "fmi2Terminate")

    def freeInstance(self) -> None:  # noqa: N802
        self.mode = "none"
        self._check(lib().ssx_fmu_free_instance(self.fmu), "fmi2FreeInstance")

    # ------------------------------------------------------------ values
    def _vrs(self, vr: Sequence[int]) -> tuple[Any, int]:
        refs = list(vr)
        return ffi.new("unsigned int[]", refs), len(refs)

    def getReal(self, vr: Sequence[int]) -> list[float]:  # noqa: N802
        refs, n = self._vrs(vr)
        values = ffi.new("double[]", n)
        self._check(lib().ssx_fmu_get_real(self.fmu, refs, n, values), "fmi2GetReal")
        return list(values)

    def setReal(self, vr: Sequence[int], values: Sequence[float]) -> None:  # noqa: N802
        refs, n = self._vrs(vr)
        self._check(lib().ssx_fmu_set_real(self.fmu, refs, n, ffi.new("double[]", list(values))),
                    "fmi2SetReal")

    def getInteger(self, vr: Sequence[int]) -> list[int]:  # noqa: N802
        refs, n = self._vrs(vr)
        values = ffi.new("int[]", n)
        self._check(lib().ssx_fmu_get_integer(self.fmu, refs, n, values), "fmi2GetInteger")
        return list(values)

    def setInteger(self, vr: Sequence[int], values: Sequence[int]) -> None:  # noqa: N802
        refs, n = self._vrs(vr)
        self._check(lib().ssx_fmu_set_integer(self.fmu, refs, n,
                                              ffi.new("int[]", [int(v) for v in values])),
                    "fmi2SetInteger")

    def getBoolean(self, vr: Sequence[int]) -> list[bool]:  # noqa: N802
        refs, n = self._vrs(vr)
        values = ffi.new("int[]", n)
        self._check(lib().ssx_fmu_get_boolean(self.fmu, refs, n, values), "fmi2GetBoolean")
        return [bool(v) for v in values]

    def setBoolean(self, vr: Sequence[int], values: Sequence[bool]) -> None:  # noqa: N802
        refs, n = self._vrs(vr)
        self._check(lib().ssx_fmu_set_boolean(self.fmu, refs, n,
                                              ffi.new("int[]", [int(bool(v)) for v in values])),
                    "fmi2SetBoolean")

    # texts (every standard) and FMI 3.0's bytes (other FMUs refuse them)
    def getString(self, vr: Sequence[int]) -> list[str]:  # noqa: N802
        refs, n = self._vrs(vr)
        values = ffi.new("const char *[]", n)
        self._check(lib().ssx_fmu_get_string(self.fmu, refs, n, values), "fmi2GetString")
        return [string(v) for v in values]

    def setString(self, vr: Sequence[int], values: Sequence[str]) -> None:  # noqa: N802
        refs, n = self._vrs(vr)
        texts = [ffi.new("char[]", str(v).encode()) for v in values]
        self._check(lib().ssx_fmu_set_string(self.fmu, refs, n,
                                             ffi.new("const char *[]", texts)), "fmi2SetString")

    def getBinary(self, vr: Sequence[int]) -> list[bytes]:  # noqa: N802
        refs, n = self._vrs(vr)
        sizes = ffi.new("size_t[]", n)
        values = ffi.new("const unsigned char *[]", n)
        self._check(lib().ssx_fmu_get_binary(self.fmu, refs, n, sizes, values),
                    "fmi3GetBinary")
        return [ffi.buffer(values[k], sizes[k])[:] for k in range(n)]

    def setBinary(self, vr: Sequence[int], values: Sequence[bytes]) -> None:  # noqa: N802
        refs, n = self._vrs(vr)
        arrays = [ffi.new("unsigned char[]", bytes(v)) for v in values]
        sizes = ffi.new("size_t[]", [len(v) for v in values])
        self._check(lib().ssx_fmu_set_binary(self.fmu, refs, n, sizes,
                                             ffi.new("const unsigned char *[]", arrays)),
                    "fmi3SetBinary")

    # ------------------------------------------------------------ states
    def getFMUstate(self, state: FMUState | None = None) -> FMUState:  # noqa: N802
        """A new state, or `state` overwritten with the current one."""
        if state is not None and state.generation == self.generation:
            self._check(lib().ssx_fmu_get_state(self.fmu, state.handle), "fmi2GetFMUstate")
            return state
        handle = ffi.new("void **")
        self._check(lib().ssx_fmu_get_state(self.fmu, handle), "fmi2GetFMUstate")
        return FMUState(self, handle)

    def setFMUstate(self, state: FMUState) -> None:  # noqa: N802
        if state.generation != self.generation:
            raise FMUError(f"{self.component_name}: the FMU state belongs to an instance that "
                           "was freed or replaced", component=self.component_name)
        self._check(lib().ssx_fmu_set_state(self.fmu, state.handle[0]), "fmi2SetFMUstate")

    def freeFMUstate(self, state: FMUState) -> None:  # noqa: N802
        state.free()

    def serializeFMUstate(self, state: FMUState) -> bytes:  # noqa: N802
        size = ffi.new("size_t *")
        self._check(lib().ssx_fmu_serialized_state_size(self.fmu, state.handle[0], size),
                    "fmi2SerializedFMUstateSize")
        buffer = ffi.new("char[]", size[0])
        self._check(lib().ssx_fmu_serialize_state(self.fmu, state.handle[0], buffer, size[0]),
                    "fmi2SerializeFMUstate")
        return ffi.buffer(buffer, size[0])[:]

    def deserializeFMUstate(self, serializedState: bytes,  # noqa: N802,N803
                            state: FMUState | None = None) -> FMUState:
        if state is not None and state.generation == self.generation:
            self._check(lib().ssx_fmu_deserialize_state(self.fmu, serializedState,
                                                        len(serializedState), state.handle),
                        "fmi2DeSerializeFMUstate")
            return state
        handle = ffi.new("void **")
        self._check(lib().ssx_fmu_deserialize_state(self.fmu, serializedState,
                                                    len(serializedState), handle),
                    "fmi2DeSerializeFMUstate")
        return FMUState(self, handle)

    # FMPy spells these both ways.
    getFMUState = getFMUstate  # noqa: N815
    setFMUState = setFMUstate  # noqa: N815
    freeFMUState = freeFMUstate  # noqa: N815
    serializeFMUState = serializeFMUstate  # noqa: N815
    deserializeFMUState = deserializeFMUstate  # noqa: N815


def start_values(starts: Values) -> tuple[Any, list[Any]]:
    """The ssx_fmu_values of `starts`, and the arrays it points at (keep them alive)."""
    values = ffi.new("ssx_fmu_values *")
    keep: list[Any] = [values]
    for kind, (refs, vals) in starts.items():
        vr_field, values_field, count_field, c_type, convert = _VALUES_LAYOUT[kind]
        items = [convert(v) for v in vals]
        vr, array = ffi.new("unsigned int[]", list(refs)), ffi.new(c_type, items)
        keep += [vr, array]
        setattr(values, vr_field, vr)
        setattr(values, values_field, array)
        setattr(values, count_field, len(items))
    return values, keep


# layouts of start values an instance keeps (a user's loop may write ever other subsets)
_KEPT_LAYOUTS = 8


def _boolean(value: Any) -> int:
    return int(bool(value))


# per value type: the ssx_fmu_values fields, the C array type and the conversion of a value
_VALUES_LAYOUT: dict[PortType, tuple[str, str, str, str, Callable[[Any], Any]]] = {
    PortType.REAL: ("real_vr", "real_values", "n_real", "double[]", float),
    PortType.INT: ("integer_vr", "integer_values", "n_integer", "int[]", int),
    PortType.BOOL: ("boolean_vr", "boolean_values", "n_boolean", "int[]", _boolean)}
