"""Core vocabulary: ports, events and the component base class."""

from .events import DenseTime, EventIndicator
from .port import Port, PortSpec, PortState, PortType

__all__ = ["DenseTime", "EventIndicator", "Port", "PortSpec", "PortState", "PortType"]
