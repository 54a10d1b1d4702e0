"""How a port reads in reports and pictures: its kind and its unit as text."""

from __future__ import annotations

from typing import Any


def port_kind(spec: Any) -> str:
    """"real", "int", "bool", "string" or "event" (the PortType value, or its name)."""
    return str(getattr(spec.type, "value", spec.type)).lower()


def unit_text(unit: Any) -> str | None:
    """The unit as written (a string or a pint Unit), None when dimensionless or absent."""
    text = "" if unit is None else str(unit)
    return text or None


def port_label(spec: Any) -> str:
    """"theta [rad]" for a real port, "omega_invert (event)" for the others."""
    kind = port_kind(spec)
    if kind == "real":
        unit = unit_text(spec.unit)
        return f"{spec.name} [{unit}]" if unit else spec.name
    return f"{spec.name} ({kind})"


def connection_unit_label(src_spec: Any, dst_spec: Any) -> str | None:
    """"rad" when both ends agree, "m -> cm" when the connection converts, else None."""
    src = unit_text(src_spec.unit) if src_spec is not None else None
    dst = unit_text(dst_spec.unit) if dst_spec is not None else None
    if src and dst and src != dst:
        return f"{src} -> {dst}"
    return src or dst
