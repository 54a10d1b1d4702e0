"""A power-bonded OSP system for libcosim's ECCO algorithm: a pendulum FMU and the torsion
spring-damper FMU, the spring's other end held at rest, joined by a torque/angular velocity
bond (the pendulum gives omega and takes the torque; the spring takes omega and gives the
torque). Written with FMU copies for syssimx.osp and for libcosim, and its monolithic
solution (solve_ivp, rtol 1e-12)."""

from __future__ import annotations

import shutil
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from syssimx import fmus

M, L, G, INERTIA = 40.0, 0.6, 9.81, 20.0  # the pendulum FMU's defaults
K, D = 100.0, 1.0
THETA0 = 0.5
STOP_TIME = 4.0
CVODE_RTOL = 1e-10  # the pendulum's own integration: far below the coupling errors


@dataclass(frozen=True)
class Ecco:
    """An <EccoConfiguration>; every element is required by libcosim's schema."""

    tolerance: float
    step_size: float = 1e-3
    min_step: float = 1e-5
    max_step: float = 0.05
    safety: float = 0.9
    min_change: float = 0.2
    max_change: float = 1.5
    p_gain: float = 0.2
    i_gain: float = 0.15

    def xml(self) -> str:
        elements = {"SafetyFactor": self.safety, "StepSize": self.step_size,
                    "MinimumStepSize": self.min_step, "MaximumStepSize": self.max_step,
                    "MinimumChangeRate": self.min_change, "MaximumChangeRate": self.max_change,
                    "ProportionalGain": self.p_gain, "IntegralGain": self.i_gain,
                    "RelativeTolerance": self.tolerance, "AbsoluteTolerance": self.tolerance}
        return "\n".join(f"    <{name}>{value!r}</{name}>" for name, value in elements.items())


STRUCTURE = """<?xml version="1.0" encoding="UTF-8"?>
<OspSystemStructure xmlns="http://opensimulationplatform.com/MSMI/OSPSystemStructure"
                    version="0.1">
  <StartTime>0.0</StartTime>
  <BaseStepSize>{step_size!r}</BaseStepSize>
  <Algorithm>ecco</Algorithm>
  <Simulators>
    <Simulator name="Pendulum" source="fmus/pendulum_cvode.fmu">
      <InitialValues>
        <InitialValue variable="theta0"><Real value="{theta0!r}"/></InitialValue>
        <InitialValue variable="cvode_relative_tolerance"><Real value="{rtol!r}"/></InitialValue>
      </InitialValues>
    </Simulator>
    <Simulator name="Spring" source="fmus/torsion_spring.fmu">
      <InitialValues>
        <InitialValue variable="k"><Real value="{k!r}"/></InitialValue>
        <InitialValue variable="d"><Real value="{d!r}"/></InitialValue>
      </InitialValues>
    </Simulator>
  </Simulators>
  <Connections>
    <VariableConnection powerBond="shaft">
      <Variable simulator="Pendulum" name="omega" causality="output"/>
      <Variable simulator="Spring" name="omega1" causality="input"/>
    </VariableConnection>
    <VariableConnection powerBond="shaft">
      <Variable simulator="Spring" name="tau1" causality="output"/>
      <Variable simulator="Pendulum" name="torque" causality="input"/>
    </VariableConnection>
    <VariableConnection>
      <Variable simulator="Pendulum" name="theta"/>
      <Variable simulator="Spring" name="theta1"/>
    </VariableConnection>
  </Connections>
  <EccoConfiguration>
{ecco}
  </EccoConfiguration>
</OspSystemStructure>
"""


def write_structure(folder: Path, ecco: Ecco) -> Path:
    """OspSystemStructure.xml in `folder`, the two FMUs in folder/fmus."""
    (folder / "fmus").mkdir(parents=True, exist_ok=True)
    for fmu in ("pendulum_cvode", "torsion_spring"):
        shutil.copy(fmus.path(fmu), folder / "fmus" / f"{fmu}.fmu")
    path = folder / "OspSystemStructure.xml"
    path.write_text(STRUCTURE.format(step_size=ecco.step_size, theta0=THETA0, rtol=CVODE_RTOL,
                                     k=K, d=D, ecco=ecco.xml()))
    return path


def monolithic(t: np.ndarray) -> np.ndarray:
    """theta at the times t of the pendulum with the spring-damper to rest."""
    def rhs(_: float, y: np.ndarray) -> list[float]:
        torque = -K * y[0] - D * y[1]
        return [y[1], (-M * G * L * np.sin(y[0]) + torque) / INERTIA]

    return solve_ivp(rhs, (0.0, float(np.max(t))), [THETA0, 0.0], t_eval=t, rtol=1e-12,
                     atol=1e-14, method="DOP853").y[0]
