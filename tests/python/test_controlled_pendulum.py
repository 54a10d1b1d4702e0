"""A PI controller FMU holds the pendulum FMU at an angle, through a feedthrough path.

Wiring (Gauss-Seidel; no algebraic loop, since the pendulum's outputs are its states):

    P.theta -> PI.measurement, P.theta -> Spring.theta1, P.omega -> Spring.omega1
    Spring.tau1 -> Torque.spring, PI.u -> Torque.control, Torque.torque -> P.torque

The spring-damper is tied to the ground (its theta2 and omega2 are unconnected and keep their
start 0), and Torque is a Python component with declared feedthrough torque = spring + control.

Derivation by hand. With e = theta_sp - theta and z = integral of e, the closed loop is

    I theta'' = -m g L sin(theta) - k theta - d omega + kp e + ki z,    z' = e.

At rest z' = 0 gives theta = theta_sp, and omega = 0, theta'' = 0 give the controller output
PI.u = ki z = m g L sin(theta_sp) + k theta_sp: the controller carries gravity and the spring.
Linearized about that rest point (x = theta - theta_sp, z = z_ss + zeta):

    I x''' + d x'' + (m g L cos(theta_sp) + k + kp) x' + ki x = 0.

Routh-Hurwitz for a cubic a3 s^3 + a2 s^2 + a1 s + a0 with positive coefficients: stable iff
a2 a1 > a3 a0, that is d (m g L cos(theta_sp) + k + kp) > I ki. Without the damper (d = 0) the
s^2 coefficient vanishes and no choice of kp, ki stabilizes the pendulum: hence the spring-damper.
"""

from __future__ import annotations

import shutil
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from typing import Any

import numpy as np
import pytest
from syssimx import (
    Connection,
    CoSimComponent,
    FMUComponent,
    GaussSeidelAlgorithm,
    PortSpec,
    PortType,
    System,
    fmus,
)

M, L, G, INERTIA = 40.0, 0.6, 9.81, 20.0  # the pendulum FMU's defaults
STIFFNESS, DAMPING = 100.0, 60.0
KP, KI = 300.0, 200.0
THETA_SP = 0.3
TF, DT = 60.0, 0.01

STEADY_CONTROL = M * G * L * np.sin(THETA_SP) + STIFFNESS * THETA_SP
CHARACTERISTIC = [INERTIA, DAMPING, M * G * L * np.cos(THETA_SP) + STIFFNESS + KP, KI]
SLOWEST_RATE = float(max(np.roots(CHARACTERISTIC).real))  # about -0.329 1/s


class TorqueSum(CoSimComponent):
    """torque = spring + control, at once (declared feedthrough, no state)."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        for port in ("spring", "control"):
            self.input_specs[port] = PortSpec(port, PortType.REAL, "in", "N.m")
        self.output_specs["torque"] = PortSpec("torque", PortType.REAL, "out", "N.m")
        self.direct_feedthrough = {"torque": {"spring", "control"}}

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _total(self) -> float:
        return float(self.inputs["spring"].raw() + self.inputs["control"].raw())

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        self.outputs["torque"].set(self._total(), t)

    def evaluate_outputs(self, inputs: Mapping[str, Any], t: float | None = None
                         ) -> dict[str, Any]:
        for name, value in inputs.items():
            self.inputs[name].set(value, t)
        return {"torque": self._total()}


def controlled_pendulum() -> System:
    pendulum = FMUComponent("P", fmus.path("pendulum_cvode"), group="Mechanical")
    pendulum.set_parameters(cvode_relative_tolerance=1e-10)
    spring = FMUComponent("Spring", fmus.path("torsion_spring"), group="Mechanical")
    spring.set_parameters(k=STIFFNESS, d=DAMPING)
    controller = FMUComponent("PI", fmus.path("pi_controller"), group="Control")
    controller.set_parameters(kp=KP, ki=KI)
    controller.set_inputs({"setpoint": THETA_SP})  # unconnected: keeps this start value
    system = System("controlled pendulum")
    for component in (pendulum, spring, controller, TorqueSum("Torque")):
        system.add_component(component)
    for wire in (("P", "theta", "PI", "measurement"), ("P", "theta", "Spring", "theta1"),
                 ("P", "omega", "Spring", "omega1"), ("Spring", "tau1", "Torque", "spring"),
                 ("PI", "u", "Torque", "control"), ("Torque", "torque", "P", "torque")):
        system.add_connection(Connection(*wire))
    system.set_algorithm(GaussSeidelAlgorithm())
    return system


def test_the_chosen_gains_satisfy_the_stability_condition():
    a3, a2, a1, a0 = CHARACTERISTIC
    assert a2 * a1 > a3 * a0
    assert -0.35 < SLOWEST_RATE < -0.3
    # the same polynomial without damping has a root on or right of the imaginary axis
    assert max(np.roots([a3, 0.0, a1, a0]).real) > -1e-12


def test_pi_controller_reaches_the_hand_derived_steady_state():
    system = controlled_pendulum()
    system.initialize(0.0)
    result = system.run(0.0, TF, DT)
    t, pendulum = result["P"]
    control = result["PI"][1]["u"]
    assert t[-1] == pytest.approx(TF)
    assert result.statistics.loop_solves == 0  # a feedthrough path, not an algebraic loop

    # Near rest the error is a sum of modes; the fast pair decays like exp(-1.34 t), the slowest
    # like exp(SLOWEST_RATE t): exp(-0.329 * 60) = 2.6e-9. Its amplitude is of the order of the
    # start's offset from rest (0.3 rad, 100 N.m; the run shows about half of it, the error
    # shrinks by exp(-3.29) per 10 s): allowing ten times the offset gives the tolerances.
    decay = np.exp(SLOWEST_RATE * TF)
    assert decay < 3e-9
    assert abs(pendulum["theta"][-1] - THETA_SP) < 10 * THETA_SP * decay
    assert abs(control[-1] - STEADY_CONTROL) < 10 * STEADY_CONTROL * decay
    assert abs(pendulum["omega"][-1]) < 10 * THETA_SP * decay
    # not settled by accident early on: a third of the way the error is still visible
    third = np.searchsorted(t, TF / 3)
    assert abs(pendulum["theta"][third] - THETA_SP) > 1e-5


@pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz 'dot' missing")
def test_jupyter_picture_shows_every_component_and_connection():
    system = controlled_pendulum()
    svg = system._repr_svg_()
    root = ET.fromstring(svg)
    namespace = "{http://www.w3.org/2000/svg}"
    texts = {"".join(node.itertext()) for node in root.iter(f"{namespace}text")}
    assert {"P", "Spring", "PI", "Torque"} <= texts
    edges = {g.get("id") for g in root.iter(f"{namespace}g")
             if g.get("class", "").startswith("edge")}
    assert edges == {f"connection:{c.src_comp}.{c.src_port}->{c.dst_comp}.{c.dst_port}"
                     for c in system.connections}
