"""Connected values reach the inputs inside initialization mode (issue 33, item 4).

preloaded_spring sets its torque state from its angle input when it leaves initialization
mode, tau(0) = -k (angle(0) - angle0), then integrates tau' = -k omega, as maestro's 20-sim
MassSpringDamper2 computes its force on leaving initialization mode. Driven by a pendulum
released at theta0 = 0.5, the torque at t0 says which angle the spring saw when it left: the
pendulum's (the connected inputs set in initialization mode, as libcosim and Ecos do), or the
input's start value 0 (set after it, as syssimx did: the spring started at +10 N.m instead of
-40 N.m and kept that offset).

Later values: with the inputs held over a step, the spring's Euler back-end integrates the
constant tau' exactly. The spring steps first (Gauss-Seidel runs the consumer of a delayed
output before its producer) and holds omega(t_(n-1)) over the step to t_n, so
tau(t_n) = tau(t0) - k h sum_{i=0..n-1} omega_in(t_i), with omega_in what the pendulum recorded
times the connection's factor: a manual master's recurrence, checked to rounding.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import pytest
from fixture_fmus import fmu_path
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

THETA0 = 0.5
K, ANGLE0 = 100.0, 0.1  # preloaded_spring's defaults
DT, TF = 0.01, 1.0


class Doubler(CoSimComponent):
    """y = 2 u, at once (declared feedthrough, no state): a Python component on the way."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.input_specs["u"] = PortSpec("u", PortType.REAL, "in", "rad")
        self.output_specs["y"] = PortSpec("y", PortType.REAL, "out", "rad")
        self.direct_feedthrough = {"y": {"u"}}

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        self.outputs["y"].set(2.0 * float(self.inputs["u"].raw()), t)

    def evaluate_outputs(self, inputs: Mapping[str, Any], t: float | None = None
                         ) -> dict[str, Any]:
        for name, value in inputs.items():
            self.inputs[name].set(value, t)
        return {"y": 2.0 * float(self.inputs["u"].raw())}


def spring_system(spring_fmu: str, interface: str = "auto", factor: float = 1.0,
                  offset: float = 0.0, algorithm: Any = None) -> System:
    pendulum = FMUComponent("P", fmus.path("pendulum_cvode"))
    pendulum.set_parameters(theta0=THETA0, cvode_relative_tolerance=1e-10)
    spring = FMUComponent("S", fmu_path(spring_fmu), interface=interface, tolerance=1e-10)
    system = System("preloaded")
    system.add_component(pendulum)
    system.add_component(spring)
    system.add_connection(Connection("P", "theta", "S", "angle", factor=factor, offset=offset))
    system.add_connection(Connection("P", "omega", "S", "omega", factor=factor))
    system.set_algorithm(algorithm if algorithm is not None else GaussSeidelAlgorithm())
    return system


def held_omega_recurrence(tau0: float, omega_in: np.ndarray) -> np.ndarray:
    """tau(t_n) = tau0 - k h sum_{i=0..n-1} omega_in(t_i): the spring holds the value of each
    step's start."""
    return tau0 - K * DT * np.concatenate(([0.0], np.cumsum(omega_in[:-1])))


@pytest.mark.parametrize("spring_fmu", ["preloaded_spring", "preloaded_spring_fmi3",
                                        "preloaded_spring_fmi1"])
def test_the_spring_leaves_initialization_mode_with_the_pendulums_angle(spring_fmu):
    """Co-Simulation, FMI 2.0, 3.0 and 1.0 (inputs set before fmiInitializeSlave); the
    connections' factor and offset apply as in any step: angle(0) = 2 * 0.5 + 0.1."""
    system = spring_system(spring_fmu, factor=2.0, offset=0.1)
    system.initialize(0.0)
    result = system.run(0.0, TF, DT)
    t, spring = result["S"]
    omega = result["P"][1]["omega"]
    tau0 = -K * (2.0 * THETA0 + 0.1 - ANGLE0)  # -100 N.m
    assert spring["tau"][0] == pytest.approx(tau0, rel=1e-15)
    np.testing.assert_allclose(spring["tau"], held_omega_recurrence(tau0, 2.0 * omega),
                               rtol=1e-12, atol=1e-9)
    # the spring follows the pendulum: tau = -k (angle - angle0) to the coupling's O(h)
    np.testing.assert_allclose(spring["tau"], -K * (2.0 * result["P"][1]["theta"] + 0.1
                                                    - ANGLE0), atol=2.0)
    assert t[-1] == TF


@pytest.mark.parametrize(("spring_fmu", "interface"), [
    ("preloaded_spring", "model-exchange"), ("preloaded_spring_fmi1_me", "auto")])
def test_a_model_exchange_spring_leaves_initialization_mode_with_the_pendulums_angle(
        spring_fmu, interface):
    """FMI 2.0 and 1.0 (inputs set before fmiInitialize)."""
    system = spring_system(spring_fmu, interface=interface)
    system.initialize(0.0)
    result = system.run(0.0, TF, DT)
    spring, omega = result["S"][1]["tau"], result["P"][1]["omega"]
    tau0 = -K * (THETA0 - ANGLE0)
    assert spring[0] == pytest.approx(tau0, rel=1e-15)
    # CVODE integrates the held omega (a constant slope) to its tolerance
    np.testing.assert_allclose(spring, held_omega_recurrence(tau0, omega), rtol=1e-7,
                               atol=1e-7)


@pytest.mark.parametrize("algorithm", [GaussSeidelAlgorithm(), JacobiAlgorithm()],
                         ids=["gauss-seidel", "jacobi"])
def test_the_input_at_t0_equals_the_driving_pendulums_angle(algorithm):
    """Before: the spring read angle(0) = 0 while the pendulum stood at 0.5 (tau(0) = +10)."""
    system = spring_system("preloaded_spring", algorithm=algorithm)
    system.initialize(0.0)
    assert system.components["S"].get_outputs()["tau"].magnitude == pytest.approx(
        -K * (THETA0 - ANGLE0), rel=1e-15)
    assert system.components["S"].inputs["angle"].raw() == THETA0


def test_a_python_component_between_passes_its_value_before_the_spring_leaves():
    pendulum = FMUComponent("P", fmus.path("pendulum_cvode"))
    pendulum.set_parameters(theta0=THETA0)
    spring = FMUComponent("S", fmu_path("preloaded_spring"))
    system = System("through Python")
    for component in (spring, Doubler("D"), pendulum):  # added against the data's order
        system.add_component(component)
    system.add_connection(Connection("P", "theta", "D", "u"))
    system.add_connection(Connection("D", "y", "S", "angle"))
    system.initialize(0.0)
    assert spring.get_outputs()["tau"].magnitude == pytest.approx(-K * (2 * THETA0 - ANGLE0),
                                                                  rel=1e-15)


def test_initializing_again_gives_the_inputs_again():
    """A reused plan: the second initialize starts from the pendulum's angle again, not from
    the value the input held at the end of the first run."""
    system = spring_system("preloaded_spring")
    system.initialize(0.0)
    system.run(0.0, 0.5, DT)
    system.initialize(0.0)
    assert system.get_history()["S"][1]["tau"][0] == pytest.approx(-K * (THETA0 - ANGLE0),
                                                                    rel=1e-15)


def test_an_algebraic_loop_upstream_is_solved_before_the_spring_leaves():
    """gain: g = u_g; sum: s = 1 - 0.005 u_s, u_s in cm fed g in m (x 100); u_g = s. The loop
    is iterated in initialization mode and solved once its members left: s = 1 - 0.5 s, so
    s = 2/3, which the spring's angle receives."""
    gain = FMUComponent("G", fmus.path("gain"))
    total = FMUComponent("T", fmus.path("sum"))
    total.set_parameters(b=1.0, c=0.005)
    spring = FMUComponent("S", fmu_path("preloaded_spring"))
    system = System("loop upstream")
    for component in (spring, gain, total):
        system.add_component(component)
    system.add_connection(Connection("G", "y", "T", "u"))
    system.add_connection(Connection("T", "y", "G", "u"))
    system.add_connection(Connection("T", "y", "S", "angle", convert_units=False))
    system.initialize(0.0)
    history = system.get_history()
    assert history["T"][1]["y"][0] == pytest.approx(2.0 / 3.0, rel=1e-9)
    assert history["S"][1]["tau"][0] == pytest.approx(-K * (2.0 / 3.0 - ANGLE0), rel=1e-9)
