"""The exceptions syssimx raises. Every one derives from SysSimXError."""

from __future__ import annotations


class SysSimXError(Exception):
    """Base class of every syssimx error."""

    def __str__(self) -> str:
        # a safety net: a user never sees an empty message, at worst what kind of error it is
        text = super().__str__()
        return text or (type(self).__doc__ or type(self).__name__).strip().splitlines()[0]


class SysSimXWarning(UserWarning):
    """Something syssimx did that a user may not expect, and went on: a last step shorter than
    dt, a parameter set after initialize that waits for the next one."""


class ConfigurationError(SysSimXError, ValueError):
    """Bad input found before anything runs: unknown names, wrong types, bad units or times."""


class ConfigurationTypeError(ConfigurationError, TypeError):
    """A value of the wrong type for a port, a parameter or an option (also a TypeError)."""


class UnknownNameError(ConfigurationError, KeyError):
    """A name a result or a history does not hold: a component, a port, an event (also a
    KeyError, as for a mapping)."""

    def __str__(self) -> str:
        # KeyError quotes its message; this one reads as the other errors do
        return BaseException.__str__(self) or SysSimXError.__str__(self)


class BundledFMUNotFoundError(ConfigurationError, FileNotFoundError):
    """No FMU of that name is bundled with syssimx (also a FileNotFoundError)."""


class FMUFileError(ConfigurationError):
    """The .fmu file cannot be used: missing, a broken or hostile archive, an invalid
    modelDescription, no binary for this platform."""


class FMUError(SysSimXError):
    """An fmi2 call returned Error or Fatal (or the engine could not make the call)."""

    def __init__(self, message: str, *, component: str | None = None, status: int | None = None,
                 fmu_message: str = "") -> None:
        super().__init__(message)
        self.component = component
        self.status = status
        self.fmu_message = fmu_message


class StateError(SysSimXError):
    """A system's state cannot be saved, restored or turned into bytes: names the component
    that cannot (its `component`, None when the system as a whole is the cause)."""

    def __init__(self, message: str, *, component: str | None = None) -> None:
        super().__init__(message)
        self.component = component


class SimulationError(SysSimXError):
    """A run failed. Names the component, the simulation time, the fmi2 status and the FMU's
    last log message when they are known; samples recorded before the failure stay readable."""

    def __init__(self, message: str, *, component: str | None = None, time: float | None = None,
                 status: int | None = None, fmu_message: str = "", event: str | None = None
                 ) -> None:
        super().__init__(message)
        self.component = component
        self.time = time
        self.status = status
        self.fmu_message = fmu_message
        self.event = event


class SimulationTimeoutError(SimulationError, TimeoutError):
    """A run took longer than its `timeout` of wall time; the samples up to there are kept."""


class ZenoError(SimulationError):
    """Events chatter (Zeno behaviour) or one instant needs more than max_microsteps rounds."""


class AlgebraicLoopError(SimulationError):
    """An algebraic loop did not converge within the loop options."""


class EngineMismatchError(SysSimXError, ImportError):
    """The engine library and its cffi module come from different engine headers (a stale
    build): calls between them could pass the wrong arguments."""


class MissingDependencyError(SysSimXError, ModuleNotFoundError):
    """An optional library a feature needs is not installed; the message names the extra that
    installs it."""


class RunInterrupted(KeyboardInterrupt):
    """Ctrl-C (SIGINT) stopped a run or a sweep. `partial_result` holds what was finished (a
    SimulationResult up to the last completed step, or an EnsembleResult of the finished
    members, the others marked failed); `partial` is always True. A KeyboardInterrupt, so code
    that stops on Ctrl-C still does."""

    partial = True

    def __init__(self, message: str, partial_result: object) -> None:
        super().__init__(message)
        self.partial_result = partial_result


class RunTerminated(SystemExit):
    """SIGTERM stopped a run: as for Ctrl-C, `partial_result` holds the samples up to the last
    completed step and a streamed file holds the same. A SystemExit with status 143 (128 +
    SIGTERM), so that a program that does not catch it ends as the signal asked, its cleanup
    done; the message is in `message`."""

    partial = True

    def __init__(self, message: str, partial_result: object) -> None:
        super().__init__(143)
        self.message = message
        self.partial_result = partial_result

    def __str__(self) -> str:
        return self.message
