"""A chain of gain FMUs added in the reverse of its schedule, so that the engine's port block
(every component's inputs and outputs, in schedule order, laid out by initialize) differs from
the order of adding. Each sample is checked against the closed form y_i = K_i u, K_i the
product of the gains up to i (the same products the FMUs compute, so equality is exact): under
Gauss-Seidel the whole chain follows the input within the step, under Jacobi stage i follows it
i + 1 steps later. A Python component in the chain and an observer read and write the ports
where initialize put them."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from syssimx import (
    Connection,
    CoSimComponent,
    FMUComponent,
    GaussSeidelAlgorithm,
    JacobiAlgorithm,
    PortSpec,
    PortType,
    System,
    fmus,
)

GAINS = [1.5, -2.0, 0.5, 3.0, 1.25]


def _products(gains: list[float], u: float) -> list[float]:
    """y_i = k_i * y_(i-1), y_(-1) = u, multiplied in the order the FMUs do."""
    values, value = [], u
    for k in gains:
        value = k * value
        values.append(value)
    return values


def _chain(algorithm: Any) -> System:
    gains = []
    for i, k in enumerate(GAINS):
        gain = FMUComponent(f"G{i}", fmus.path("gain"))
        gain.set_parameters(k=k)
        gains.append(gain)
    # a sink closes the chain: a stage is scheduled after its driver only where its output
    # goes on (graph/analysis.py), so the last checked stage's does
    sink = FMUComponent("S", fmus.path("gain"))
    system = System("chain")
    for component in [sink, *reversed(gains)]:
        system.add_component(component)
    for i in range(1, len(gains)):
        system.add_connection(Connection(f"G{i - 1}", "y", f"G{i}", "u"))
    system.add_connection(Connection(f"G{len(gains) - 1}", "y", "S", "u"))
    gains[0].set_inputs({"u": 1.0})
    system.set_algorithm(algorithm)
    return system


@pytest.mark.parametrize("algorithm", [GaussSeidelAlgorithm, JacobiAlgorithm])
def test_each_stage_follows_its_input_as_the_coupling_says(algorithm: Any) -> None:
    system = _chain(algorithm())
    for _ in range(2):  # the second initialize reuses the plan and its block
        system.initialize(0.0)
        first = system.run(0.0, 0.5, 0.1)
        before = _products(GAINS, 1.0)
        for i in range(len(GAINS)):  # from the first step on (t0 is the FMUs' own start)
            assert first[f"G{i}"][1]["y"][1:].tolist() == [before[i]] * 5
    system.components["G0"].set_inputs({"u": 2.0})
    second = system.run(0.5, 1.0, 0.1)
    after = _products(GAINS, 2.0)
    lag = 0 if algorithm is GaussSeidelAlgorithm else 1
    for i in range(len(GAINS)):
        # the samples at 0.5 ... 1.0 (the history goes on); stage i follows i * lag steps later
        expected = [before[i]] + [after[i] if n > i * lag else before[i] for n in range(1, 6)]
        assert second[f"G{i}"][1]["y"][-6:].tolist() == expected, f"G{i}"


class Doubler(CoSimComponent):
    """y = 2 x, stepped in Python."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.input_specs.update({"x": PortSpec("x", PortType.REAL, "in", unit="m")})
        self.output_specs.update({"y": PortSpec("y", PortType.REAL, "out", unit="m")})

    def _do_step_internal(self, t: float, dt: float) -> None:
        self.doubled = 2.0 * self.inputs["x"].get()

    def _update_output_states(self, t: float | None = None, event_names: Any = None) -> None:
        self.outputs["y"].set(getattr(self, "doubled", 0.0), t)


class Keeper:
    """An observer keeping every sample's values."""

    def __init__(self) -> None:
        self.samples: list[np.ndarray] = []

    def step_complete(self, t: float, micro: int, values: np.ndarray) -> None:
        self.samples.append(values)


def test_a_python_component_and_an_observer_use_the_ports_where_initialize_put_them() -> None:
    head, tail = FMUComponent("A", fmus.path("gain")), FMUComponent("B", fmus.path("gain"))
    head.set_parameters(k=1.5)
    tail.set_parameters(k=-3.0)
    system = System("python in a chain")
    sink = FMUComponent("S", fmus.path("gain"))  # B's output goes on (see _chain)
    for component in (sink, tail, Doubler("P"), head):  # the reverse of the schedule
        system.add_component(component)
    system.add_connection(Connection("A", "y", "P", "x"))
    system.add_connection(Connection("P", "y", "B", "u"))
    system.add_connection(Connection("B", "y", "S", "u"))
    head.set_inputs({"u": 1.0})
    keeper = system.add_observer(Keeper())
    system.set_algorithm(GaussSeidelAlgorithm())
    for _ in range(2):
        system.initialize(0.0)
        keeper.samples.clear()
        result = system.run(0.0, 0.3, 0.1)
        assert result["P"][1]["y"][1:].tolist() == [2.0 * 1.5] * 3
        assert result["B"][1]["y"][1:].tolist() == [-3.0 * 2.0 * 1.5] * 3
        # the observer's columns: component after component in the order of adding (the
        # sink, first, is stepped before its driver: its output is not checked)
        assert [sample[1:].tolist() for sample in keeper.samples] == [[-9.0, 3.0, 1.5]] * 3
