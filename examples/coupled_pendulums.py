"""Two pendulum FMUs coupled through the torsion spring FMU, Jacobi and Gauss-Seidel.

Co-simulation holds the spring torque constant over each macro step, so the error against the
monolithic solution (scipy solve_ivp, rtol 1e-12) is first order in dt.

    python examples/coupled_pendulums.py
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp
from syssimx import (
    Connection,
    FMUComponent,
    GaussSeidelAlgorithm,
    JacobiAlgorithm,
    System,
    fmus,
)

M, L, G, INERTIA, K, D, TF = 40.0, 0.6, 9.81, 20.0, 100.0, 1.0, 2.0


def build(algorithm: JacobiAlgorithm, rtol: float = 1e-11, torque2_factor: float = 1.0,
          torque2_offset: float = 0.0, interface: str = "auto") -> System:
    """The two pendulums and the torsion spring; the spring's torque reaches P2 as
    torque2_factor * tau2 + torque2_offset (1 and 0 here; the SSP tests scale it). With
    interface="model-exchange" the engine integrates the pendulums at the same tolerance."""
    system = System("coupled pendulums")
    for name, theta0 in (("P1", 0.5), ("P2", 0.0)):
        pendulum = FMUComponent(name, fmus.path("pendulum_cvode"), group="Mechanical",
                                tolerance=rtol, interface=interface)
        pendulum.set_parameters(theta0=theta0, cvode_relative_tolerance=rtol)
        system.add_component(pendulum)
    spring = FMUComponent("Spring", fmus.path("torsion_spring"), group="Mechanical")
    spring.set_parameters(k=K, d=D)
    system.add_component(spring)
    for i in ("1", "2"):
        system.add_connection(Connection(f"P{i}", "theta", "Spring", f"theta{i}"))
        system.add_connection(Connection(f"P{i}", "omega", "Spring", f"omega{i}"))
    system.add_connection(Connection("Spring", "tau1", "P1", "torque"))
    system.add_connection(Connection("Spring", "tau2", "P2", "torque", factor=torque2_factor,
                                     offset=torque2_offset))
    system.set_algorithm(algorithm)
    return system


def monolithic(t: np.ndarray) -> np.ndarray:
    def rhs(_: float, y: np.ndarray) -> list[float]:
        tau = -K * (y[0] - y[2]) - D * (y[1] - y[3])
        return [y[1], (-M * G * L * np.sin(y[0]) + tau) / INERTIA,
                y[3], (-M * G * L * np.sin(y[2]) - tau) / INERTIA]

    return solve_ivp(rhs, (0.0, TF), [0.5, 0.0, 0.0, 0.0], t_eval=t, rtol=1e-12,
                     atol=1e-14, method="DOP853").y[[0, 2]]


def main() -> None:
    print(f"{'algorithm':<14}{'dt':>8}{'max |theta error| [rad]':>26}")
    for algorithm in (JacobiAlgorithm, GaussSeidelAlgorithm):
        for dt in (0.04, 0.02, 0.01):
            system = build(algorithm())
            system.initialize(0.0)
            result = system.run(0.0, TF, dt)
            t, p1 = result["P1"]
            reference = monolithic(t)
            error = max(np.abs(p1["theta"] - reference[0]).max(),
                        np.abs(result["P2"][1]["theta"] - reference[1]).max())
            print(f"{algorithm().name:<14}{dt:>8}{error:>26.3e}")


if __name__ == "__main__":
    main()
