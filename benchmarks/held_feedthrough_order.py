"""The order of the coupling on libcosim's quarter truck, whose FMUs cannot interpolate their
inputs and whose wheel force depends directly on its velocity input, and what gives order 2.

The wheel computes its force only in fmi2DoStep, from the velocity it was given for the step
(setting the input afterwards does not change the output). Its force at t + h is therefore the
force for the held velocity, which differs from the velocity at t + h by O(h): every force the
chassis is given is built from samples off by O(h), and the coupling is first order whatever the
order of the polynomial the held inputs follow.

Printed, at fixed communication steps STEPS over STOP_TIME (both FMUs' timeStep set to 1e-7 so
that their own Euler error is the same in every run; error: the largest chassis velocity error
on a 0.01 s grid):

- syssimx, the truck coupled explicitly (undeclared_dependencies="none"), Gauss-Seidel, held
  inputs and input_order 1 and 2 with extrapolate_held_inputs, against syssimx's Richardson
  reference 2 b - a from Gauss-Seidel runs with held inputs at a = 1e-6 and b = 5e-7 s;
- a hand-written Gauss-Seidel master over the same FMUs (FMPy's FMU2Slave): the chassis steps
  first with its force held at the mean over the step of the force polynomial extrapolated
  from the last communication points (Adams-Bashforth weights), then the wheel with its
  velocity held at the mean of the polynomial through the chassis's new and past velocities
  (Adams-Moulton weights); "corrected" adds to each force sample the wheel's
  fmi2GetDirectionalDerivative d force / d in_vel times (velocity at t + h - velocity held),
  the force the wheel would have had with the velocity of t + h. The derivative is taken once,
  after initialization (the wheel computes it numerically, a constant here; each call moves its
  outputs until the next doStep, and taking it at every step gives the same errors). Its
  reference: the same master with held inputs at 1e-6 and 5e-7 s, extrapolated likewise.

    python benchmarks/held_feedthrough_order.py --truck ../shared/coupling-samples/quarter_truck
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
from syssimx import GaussSeidelAlgorithm
from syssimx.osp import read as read_osp

STOP_TIME = 0.1
GRID_STEP = 0.01
STEPS = (4e-4, 2e-4, 1e-4, 5e-5)
FMU_TIME_STEP = 1e-7
MASSES = {"Chassis": 400.0, "Wheel": 40.0}  # the OSP file's initial values


def syssimx_velocity(truck: Path, order: int, step: float) -> np.ndarray:
    system = read_osp(truck / "OspSystemStructure.xml").system
    system.undeclared_dependencies = "none"
    for name in ("chassis", "wheel"):
        system.components[name].set_parameters(timeStep=FMU_TIME_STEP)
    system.set_algorithm(GaussSeidelAlgorithm(input_order=order,
                                              extrapolate_held_inputs=order > 0))
    system.initialize(0.0)
    times, chassis = system.run(0.0, STOP_TIME, step)["chassis"]
    return np.interp(np.linspace(0.0, STOP_TIME, 11), times, chassis["velocity"])


def instantiate(truck: Path, model: str) -> tuple[FMU2Slave, dict[str, int]]:
    path = truck / f"{model}.fmu"
    description = read_model_description(str(path))
    references = {v.name: v.valueReference for v in description.modelVariables}
    fmu = FMU2Slave(guid=description.guid, unzipDirectory=extract(str(path)),
                    modelIdentifier=model, instanceName=model.lower())
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    fmu.setReal([references["mass"], references["timeStep"]], [MASSES[model], FMU_TIME_STEP])
    fmu.setString([references["solverType"]], ["Euler"])
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    return fmu, references


def extrapolated_mean(samples: list[float], order: int) -> float:
    """The mean over the next step of the polynomial through the last order + 1 samples."""
    order = min(order, len(samples) - 1)
    if order == 0:
        return samples[-1]
    if order == 1:
        return (3.0 * samples[-1] - samples[-2]) / 2.0
    return (23.0 * samples[-1] - 16.0 * samples[-2] + 5.0 * samples[-3]) / 12.0


def interpolated_mean(new: float, samples: list[float], order: int) -> float:
    """The mean over the step just taken of the polynomial through new and past samples."""
    if order == 0:
        return samples[-1]
    if order == 1 or len(samples) < 2:
        return (samples[-1] + new) / 2.0
    return (5.0 * new + 8.0 * samples[-1] - samples[-2]) / 12.0


def master_velocity(truck: Path, order: int, corrected: bool, step: float) -> np.ndarray:
    chassis, c = instantiate(truck, "Chassis")
    wheel, w = instantiate(truck, "Wheel")
    slope = (wheel.getDirectionalDerivative([w["out_spring_damper_f"]], [w["in_vel"]], [1.0])[0]
             if corrected else 0.0)
    velocities = [chassis.getReal([c["velocity"]])[0]]
    wheel.setReal([w["in_vel"]], velocities)
    forces = [wheel.getReal([w["out_spring_damper_f"]])[0]]
    steps, every = round(STOP_TIME / step), round(GRID_STEP / step)
    on_grid = [velocities[0]]
    for k in range(steps):
        t = k * step
        chassis.setReal([c["force"]], [extrapolated_mean(forces, order)])
        chassis.doStep(t, step)
        velocity = chassis.getReal([c["velocity"]])[0]
        held = interpolated_mean(velocity, velocities, order)
        wheel.setReal([w["in_vel"]], [held])
        wheel.doStep(t, step)
        forces.append(wheel.getReal([w["out_spring_damper_f"]])[0] + slope * (velocity - held))
        velocities.append(velocity)
        if (k + 1) % every == 0:
            on_grid.append(velocity)
    for fmu in (chassis, wheel):
        fmu.terminate()
        fmu.freeInstance()
    return np.array(on_grid)


def report(way: str, errors: list[float]) -> None:
    orders = [np.log2(errors[i] / errors[i + 1]) for i in range(len(errors) - 1)]
    print(f"{way:<44}" + "".join(f"{e:>10.2e}" for e in errors) + "   "
          + " ".join(f"{o:.2f}" for o in orders))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--truck", type=Path, required=True,
                        help="libcosim's quarter_truck folder (OspSystemStructure.xml, FMUs)")
    truck = parser.parse_args().truck.resolve()
    warnings.simplefilter("ignore")  # the undeclared dependencies' warning
    print(f"{'chassis velocity error at steps':<44}" + "".join(f"{s:>10.0e}" for s in STEPS)
          + "   observed orders")
    fine = [syssimx_velocity(truck, 0, step) for step in (1e-6, 5e-7)]
    reference = 2.0 * fine[1] - fine[0]
    for order in (0, 1, 2):
        report(f"syssimx, input_order {order}" + (", extrapolated" if order else ", held"),
               [float(np.abs(syssimx_velocity(truck, order, s) - reference).max())
                for s in STEPS])
    fine = [master_velocity(truck, 0, False, step) for step in (1e-6, 5e-7)]
    reference = 2.0 * fine[1] - fine[0]
    for order in (1, 2):
        for corrected in (False, True):
            report(f"hand-written master, order {order}, "
                   + ("corrected" if corrected else "as sampled"),
                   [float(np.abs(master_velocity(truck, order, corrected, s) - reference).max())
                    for s in STEPS])


if __name__ == "__main__":
    main()
