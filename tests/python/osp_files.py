"""OSP system structures for tests: the coupled pendulums (two pendulum FMUs and the torsion
spring), written as libcosim's users write them: P1's shaft joined to the spring by a variable
group connection (groups from OspModelDescription files), P2's by variable connections marked
as a power bond (torque one way, speed the other), P2's angle into the spring through a
LinearTransformation function."""

from __future__ import annotations

import shutil
from pathlib import Path

from syssimx import Connection, FMUComponent, GaussSeidelAlgorithm, System, fmus

NAMESPACE = "http://opensimulationplatform.com/MSMI/OSPSystemStructure"
RTOL = 1e-11
FACTOR, OFFSET = 0.5, 0.1

PENDULUM_GROUPS = """<?xml version="1.0" encoding="utf-8"?>
<OspModelDescription xmlns="http://opensimulationplatform.com/MSMI/OSPModelDescription"
                     version="0.1">
  <VariableGroups>
    <AngularMechanicalPort name="shaft">
      <Torque name="torque"><Variable ref="torque"/></Torque>
      <AngularDisplacement name="angle"><Variable ref="theta"/></AngularDisplacement>
      <AngularVelocity name="speed"><Variable ref="omega"/></AngularVelocity>
    </AngularMechanicalPort>
  </VariableGroups>
</OspModelDescription>
"""

SPRING_GROUPS = """<?xml version="1.0" encoding="utf-8"?>
<OspModelDescription xmlns="http://opensimulationplatform.com/MSMI/OSPModelDescription"
                     version="0.1">
  <VariableGroups>
    <AngularMechanicalPort name="left">
      <Torque name="torque"><Variable ref="tau1"/></Torque>
      <AngularDisplacement name="angle"><Variable ref="theta1"/></AngularDisplacement>
      <AngularVelocity name="speed"><Variable ref="omega1"/></AngularVelocity>
    </AngularMechanicalPort>
  </VariableGroups>
</OspModelDescription>
"""


def structure(algorithm: str = "fixedStep", extra_simulator: str = "",
              extra: str = "") -> str:
    pendulum = ('<Simulator name="{name}" source="fmus/pendulum_cvode.fmu"><InitialValues>'
                '<InitialValue variable="theta0"><Real value="{theta0}"/></InitialValue>'
                f'<InitialValue variable="cvode_relative_tolerance"><Real value="{RTOL}"/>'
                '</InitialValue></InitialValues></Simulator>')
    return f"""<?xml version="1.0" encoding="utf-8"?>
<OspSystemStructure xmlns="{NAMESPACE}" version="0.1">
  <StartTime>0.0</StartTime>
  <EndTime>0.5</EndTime>
  <BaseStepSize>0.01</BaseStepSize>
  <Algorithm>{algorithm}</Algorithm>
  <Simulators>
    {pendulum.format(name="P1", theta0=0.5)}
    {pendulum.format(name="P2", theta0=0.0)}
    <Simulator name="Spring" source="fmus/torsion_spring.fmu">
      <InitialValues>
        <InitialValue variable="k"><Real value="100"/></InitialValue>
        <InitialValue variable="d"><Real value="1"/></InitialValue>
      </InitialValues>
    </Simulator>
    {extra_simulator}
  </Simulators>
  <Functions>
    <LinearTransformation name="halved" factor="{FACTOR}" offset="{OFFSET}"/>
  </Functions>
  <Connections>
    <VariableGroupConnection>
      <VariableGroup simulator="Spring" name="left"/>
      <VariableGroup simulator="P1" name="shaft"/>
    </VariableGroupConnection>
    <VariableConnection powerBond="right">
      <Variable simulator="Spring" name="omega2" causality="input"/>
      <Variable simulator="P2" name="omega" causality="output"/>
    </VariableConnection>
    <VariableConnection powerBond="right">
      <Variable simulator="P2" name="torque" causality="input"/>
      <Variable simulator="Spring" name="tau2" causality="output"/>
    </VariableConnection>
    <SignalConnection>
      <Variable simulator="P2" name="theta"/>
      <Signal function="halved" name="in"/>
    </SignalConnection>
    <SignalConnection>
      <Signal function="halved" name="out"/>
      <Variable simulator="Spring" name="theta2"/>
    </SignalConnection>
    {extra}
  </Connections>
</OspSystemStructure>
"""


def write_osp(folder: Path, text: str | None = None, name: str = "OspSystemStructure.xml",
              groups_beside_fmus: bool = True) -> Path:
    """The structure file in `folder`, the FMUs in folder/fmus; the pendulum's model
    description beside its FMU (libcosim looks there first), the spring's beside the
    structure unless `groups_beside_fmus` puts both beside the FMUs."""
    (folder / "fmus").mkdir(parents=True, exist_ok=True)
    for fmu in ("pendulum_cvode", "torsion_spring", "gain"):
        shutil.copy(fmus.path(fmu), folder / "fmus" / f"{fmu}.fmu")
    (folder / "fmus" / "Pendulum_OspModelDescription.xml").write_text(PENDULUM_GROUPS)
    spring_folder = folder / "fmus" if groups_beside_fmus else folder
    (spring_folder / "TorsionSpring_OspModelDescription.xml").write_text(SPRING_GROUPS)
    path = folder / name
    path.write_text(structure() if text is None else text)
    return path


def python_built() -> System:
    """The same system built in Python."""
    system = System("same")
    for name, theta0 in (("P1", 0.5), ("P2", 0.0)):
        pendulum = FMUComponent(name, fmus.path("pendulum_cvode"))
        pendulum.set_parameters(theta0=theta0, cvode_relative_tolerance=RTOL)
        system.add_component(pendulum)
    spring = FMUComponent("Spring", fmus.path("torsion_spring"))
    spring.set_parameters(k=100.0, d=1.0)
    system.add_component(spring)
    for i in ("1", "2"):
        system.add_connection(Connection(f"P{i}", "omega", "Spring", f"omega{i}"))
        system.add_connection(Connection("Spring", f"tau{i}", f"P{i}", "torque"))
    system.add_connection(Connection("P1", "theta", "Spring", "theta1"))
    system.add_connection(Connection("P2", "theta", "Spring", "theta2", factor=FACTOR,
                                     offset=OFFSET))
    system.set_algorithm(GaussSeidelAlgorithm())
    return system
