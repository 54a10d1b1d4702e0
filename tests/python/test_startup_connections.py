"""add_connection finds the driver of an input without scanning the connections made so far."""

from __future__ import annotations

import pytest
from syssimx import ConfigurationError, Connection, CoSimComponent, PortSpec, PortType, System


class UnscannableList(list):
    """The system's connection list, refusing to be iterated while connections are added."""

    def __iter__(self):
        raise AssertionError("add_connection scanned the existing connections")


def relay(name: str) -> CoSimComponent:
    component = CoSimComponent(name)
    component.input_specs["u"] = PortSpec("u", PortType.REAL, "in")
    component.output_specs["y"] = PortSpec("y", PortType.REAL, "out")
    return component


def chain(length: int) -> System:
    system = System("chain")
    for i in range(length):
        system.add_component(relay(f"r{i}"))
    system.connections = UnscannableList()
    for i in range(length - 1):
        system.add_connection(Connection(f"r{i}", "y", f"r{i + 1}", "u"))
    return system


def test_connections_are_added_without_scanning_the_existing_ones():
    system = chain(50)
    assert [c.key() for c in list.__iter__(system.connections)][-1] == ("r48", "y", "r49", "u")


def test_a_second_driver_names_the_first_one():
    system = chain(50)
    with pytest.raises(ConfigurationError, match=r"^r0\.y -> r30\.u: input r30\.u is already "
                                                 r"driven by r29\.y$"):
        system.add_connection(Connection("r0", "y", "r30", "u"))
    assert len(system.connections) == 49
