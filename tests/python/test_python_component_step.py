"""A Python component's step: the engine hands its method plain floats, its input ports hold
the engine's values with their port's type (Real float, Integer int, Boolean bool), and what
its output ports hold reaches the engine, every step; a failure names the component and time."""

from __future__ import annotations

import pytest
from syssimx import Connection, CoSimComponent, FMUComponent, PortSpec, PortType, System, fmus
from syssimx.errors import SimulationError


class Probe(CoSimComponent):
    """Reads a Real, an Integer and a Boolean input; writes their sum and the step count."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.input_specs.update({
            "x": PortSpec("x", PortType.REAL, "in"), "n": PortSpec("n", PortType.INT, "in"),
            "on": PortSpec("on", PortType.BOOL, "in")})
        self.output_specs.update({"y": PortSpec("y", PortType.REAL, "out"),
                                  "steps": PortSpec("steps", PortType.INT, "out")})
        self.seen: set[tuple[type, ...]] = set()
        self.count = 0
        self.fail_at: float | None = None

    def _initialize_component(self, t0: float) -> None:
        self.count = 0

    def _do_step_internal(self, t: float, dt: float) -> None:
        if self.fail_at is not None and t >= self.fail_at:
            raise RuntimeError("probe broke")
        x, n, on = (self.inputs[p].get() for p in ("x", "n", "on"))
        self.seen.add((type(t), type(dt), type(x), type(n), type(on)))
        self.count += 1
        self.total = x + n + (1.0 if on else 0.0)

    def _update_output_states(self, t: float | None = None, event_names=None) -> None:
        self.outputs["y"].set(getattr(self, "total", 0.0), t)
        self.outputs["steps"].set(self.count, t)


def _system() -> tuple[System, Probe]:
    gain = FMUComponent("G", fmus.path("gain"))
    gain.set_parameters(k=2.0)
    gain.set_inputs({"u": 1.25})
    probe = Probe("Q")
    probe.set_inputs({"n": 3, "on": True})
    system = System("probe")
    system.add_component(gain)
    system.add_component(probe)
    system.add_connection(Connection("G", "y", "Q", "x", convert_units=False))
    return system, probe


def test_the_step_gets_plain_values_of_each_ports_type_and_its_outputs_reach_the_engine():
    system, probe = _system()
    system.initialize(0.0)
    result = system.run(0.0, 0.5, 0.1)
    assert probe.seen == {(float, float, float, int, bool)}
    outputs = result["Q"][1]
    assert outputs["y"][1:].tolist() == [2.5 + 3 + 1.0] * 5
    assert outputs["steps"].tolist() == [0, 1, 2, 3, 4, 5]
    system.initialize(0.0)  # on the same plan: the ports start again
    assert system.run(0.0, 0.2, 0.1)["Q"][1]["steps"].tolist() == [0, 1, 2]


def test_a_failing_step_names_the_component_and_time_and_keeps_the_samples():
    system, probe = _system()
    probe.fail_at = 0.3
    system.initialize(0.0)
    with pytest.raises(SimulationError,
                       match=r"^Q: do_step raised RuntimeError: probe broke at t=0\.3"):
        system.run(0.0, 0.5, 0.1)
    assert system.get_history()["Q"][1]["steps"].tolist() == [0, 1, 2, 3]
