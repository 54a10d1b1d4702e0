"""Ports: the immutable PortSpec of a component's input or output and its mutable Port value."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import StrEnum
from typing import Any, Literal

import numpy as np

from ..errors import ConfigurationError, ConfigurationTypeError
from ..units import is_quantity, magnitude_in, plainly_readable, quantity, to_unit


class PortType(StrEnum):
    """Value type of a port. EVENT ports carry event signals and never enter the engine."""

    REAL = "real"
    INT = "int"
    BOOL = "bool"
    STRING = "string"
    BINARY = "binary"  # FMI 3.0 Binary: bytes
    EVENT = "event"


Direction = Literal["in", "out"]


@dataclass(frozen=True)
class PortSpec:
    """What a port is: name, type, direction, optional unit (REAL only) and description."""

    name: str
    type: PortType
    direction: Direction
    unit: str | None = None
    description: str | None = None

    def __post_init__(self) -> None:
        if self.direction not in ("in", "out"):
            raise ConfigurationError(f"port {self.name!r}: direction must be 'in' or 'out'")
        if self.unit is not None:
            if self.type != PortType.REAL:
                raise ConfigurationError(f"port {self.name!r}: only REAL ports carry a unit")
            if not plainly_readable(str(self.unit)):  # needs no pint to know it is fine
                to_unit(str(self.unit))

    def coerce(self, value: Any) -> float | int | bool | str:
        """The plain value stored for `value` (REAL in this port's unit); TypeError if wrong."""
        if self.type == PortType.REAL:
            if is_quantity(value):
                return magnitude_in(value, self.unit)
            if isinstance(value, bool) or not isinstance(value, int | float | np.integer
                                                          | np.floating):
                raise ConfigurationTypeError(
                    f"port {self.name!r} is REAL; got {type(value).__name__}")
            return float(value)
        if self.type == PortType.INT:
            if isinstance(value, bool | np.bool_) or not isinstance(value, int | np.integer):
                raise ConfigurationTypeError(
                    f"port {self.name!r} is INT; got {type(value).__name__}")
            return int(value)
        if self.type in (PortType.BOOL, PortType.EVENT):
            if not isinstance(value, bool | np.bool_ | int | np.integer) or value not in (0, 1):
                raise ConfigurationTypeError(
                    f"port {self.name!r} is {self.type.name}; got {value!r}")
            return bool(value)
        if self.type == PortType.BINARY:
            if not isinstance(value, bytes | bytearray):
                raise ConfigurationTypeError(
                    f"port {self.name!r} is BINARY; got {type(value).__name__}")
            return bytes(value)
        if not isinstance(value, str):
            raise ConfigurationTypeError(
                f"port {self.name!r} is STRING; got {type(value).__name__}")
        return value

    def present(self, raw: float | int | bool | str) -> Any:
        """The user-facing value: a pint Quantity for a REAL port with a unit."""
        if self.type == PortType.REAL and self.unit:
            return quantity(float(raw), str(self.unit))
        return raw


_DEFAULTS: dict[PortType, float | int | bool | str] = {
    PortType.REAL: 0.0, PortType.INT: 0, PortType.BOOL: False, PortType.STRING: "",
    PortType.BINARY: b"", PortType.EVENT: False,
}

# the port types whose values the engine holds as numbers in the system's table of values
TABLED_TYPES = (PortType.STRING, PortType.BINARY)


class Port:
    """The current value of a port. `reader`, when given, supplies the value (engine-owned
    ports of FMU outputs read the engine's buffer, so they are never stale)."""

    def __init__(self, spec: PortSpec, value: Any = None,
                 reader: Callable[[], float | int | bool] | None = None) -> None:
        self.spec = spec
        self.t_last: float | None = None
        self._reader = reader
        self._raw: float | int | bool | str = (
            _DEFAULTS[spec.type] if value is None else spec.coerce(value))
        # a REAL port takes a float as it is, and one without a unit shows its plain value:
        # what a Python component's step does per port, without the general conversion
        self._real = spec.type == PortType.REAL
        self._plain = not (self._real and spec.unit)

    def set(self, value: Any, t: float | None = None) -> None:
        """Set the port's value (converted to its type), at time `t` if given."""
        self._raw = value if type(value) is float and self._real else self.spec.coerce(value)
        if t is not None:
            self.t_last = t

    def raw(self) -> float | int | bool | str:
        """The value as a plain number (REAL in the port's unit)."""
        return self._reader() if self._reader is not None else self._raw

    def get(self, as_unit: str | None = None) -> Any:
        """The value: a pint quantity where the port has a unit (in `as_unit` if given)."""
        if self._plain and self._reader is None:
            return self._raw
        value = self.spec.present(self.raw())
        if as_unit is not None and is_quantity(value):
            return value.to(to_unit(as_unit))
        return value

    @property
    def value(self) -> Any:
        """The value, as get() returns it."""
        return self.get()

    def __repr__(self) -> str:
        return f"Port({self.spec.name}={self.get()!r})"


PortState = Port  # SysSimX's name for the mutable port value
