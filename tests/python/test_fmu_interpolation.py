"""Higher-order inputs and output derivatives of the toolchain's FMUs, checked through FMPy:
fmi2SetRealInputDerivatives drives an input along its Taylor polynomial over a step (Euler and
CVODE), FMI 3.0's intermediate update lets the importer set inputs inside fmi3DoStep, and
fmi2GetRealOutputDerivatives / fmi3GetOutputDerivatives give the time derivatives of outputs
from the model's equations. References: solve_ivp at rtol 1e-12 on the same equations."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ElementTree
import zipfile

import numpy as np
import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi3 import FMU3Slave
from scipy.integrate import solve_ivp
from syssimx import fmus

M, L, G, INERTIA = 40.0, 0.6, 9.81, 20.0
THETA0 = 0.4
# the torque the importer prescribes: torque(t) = A + B t + C t^2 / 2
A, B, C = 1.0, 30.0, -40.0
T_STEP = 0.5


def torque(t: float) -> float:
    return A + B * t + 0.5 * C * t * t


def pendulum_reference(t_end: float, applied) -> tuple[float, float]:
    def rhs(t: float, y: np.ndarray) -> list[float]:
        return [y[1], (-M * G * L * math.sin(y[0]) + applied(t)) / INERTIA]

    solution = solve_ivp(rhs, (0.0, t_end), [THETA0, 0.0], rtol=1e-12, atol=1e-14,
                         method="DOP853")
    return float(solution.y[0, -1]), float(solution.y[1, -1])


@pytest.mark.parametrize(("name", "starts", "tolerance", "bound"), [
    ("pendulum_cvode", {}, 1e-10, 1e-7),
    # explicit Euler is first order in its own step: h T max|y''| / 2 ~ 1e-5 * 0.5 * 15 / 2
    ("pendulum_euler", {"euler_step_size": 1e-5}, None, 1e-4),
])
def test_input_derivatives_drive_the_input_along_its_polynomial(open_fmu, name, starts,
                                                                 tolerance, bound):
    fmu = open_fmu(name, starts={"theta0": THETA0, **starts}, tolerance=tolerance)
    fmu.set("torque", A)
    vr = fmu.vr("torque")
    fmu.slave.setRealInputDerivatives([vr, vr], [1, 2], [B, C])
    fmu.slave.doStep(0.0, T_STEP)
    theta, omega = pendulum_reference(T_STEP, torque)
    held_theta, _ = pendulum_reference(T_STEP, lambda t: A)
    assert abs(held_theta - theta) > 1e-2  # what holding the input would miss
    assert fmu.get("theta") == pytest.approx(theta, abs=bound)
    assert fmu.get("omega") == pytest.approx(omega, abs=bound)
    # after the step the input sits at its polynomial's end and goes on along it
    assert fmu.get("torque") == pytest.approx(torque(T_STEP), rel=1e-12)
    fmu.slave.doStep(T_STEP, T_STEP)
    theta, _ = pendulum_reference(2 * T_STEP, torque)
    assert fmu.get("theta") == pytest.approx(theta, abs=2 * bound)


def test_input_derivatives_are_refused_for_a_non_input(open_fmu):
    fmu = open_fmu("pendulum_cvode")
    with pytest.raises(FMICallException):
        fmu.slave.setRealInputDerivatives([fmu.vr("theta")], [1], [1.0])
    assert "is not a Real input" in fmu.messages[-1][1]
    with pytest.raises(FMICallException):
        fmu.slave.setRealInputDerivatives([fmu.vr("torque")], [3], [1.0])
    assert "order 3" in fmu.messages[-1][1]


def test_output_derivatives_follow_the_equations(open_fmu):
    pendulum = open_fmu("pendulum_cvode", starts={"theta0": THETA0, "omega0": 0.7})
    pendulum.set("torque", 3.0)
    vrs = [pendulum.vr("theta"), pendulum.vr("omega")]
    d_theta, d_omega = pendulum.slave.getRealOutputDerivatives(vrs, [1, 1])
    alpha = (-M * G * L * math.sin(THETA0) + 3.0) / INERTIA
    assert d_theta == pytest.approx(0.7, rel=1e-8)
    assert d_omega == pytest.approx(alpha, rel=1e-8)

    # the spring has no states: its torque moves only with its inputs' derivatives
    spring = open_fmu("torsion_spring")
    k, d = spring.get("k"), spring.get("d")
    names = ["theta1", "theta2", "omega1", "omega2"]
    rates = [0.3, -0.2, 1.5, 0.5]
    spring.slave.setRealInputDerivatives([spring.vr(n) for n in names], [1] * 4, rates)
    d_tau1, d_tau2 = spring.slave.getRealOutputDerivatives(
        [spring.vr("tau1"), spring.vr("tau2")], [1, 1])
    expected = -k * (rates[0] - rates[1]) - d * (rates[2] - rates[3])
    assert d_tau1 == pytest.approx(expected, rel=1e-8)
    assert d_tau2 == pytest.approx(-expected, rel=1e-8)


def test_model_descriptions_declare_the_capabilities():
    v2 = read_model_description(fmus.path("pendulum_cvode"))
    assert v2.coSimulation.canInterpolateInputs
    assert v2.coSimulation.maxOutputDerivativeOrder == 1
    v3 = read_model_description(fmus.path("pendulum_cvode_fmi3"))
    assert v3.coSimulation.providesIntermediateUpdate
    assert v3.coSimulation.maxOutputDerivativeOrder == 1
    # FMPy 0.3 does not read the variable's flag: the XML says it
    with zipfile.ZipFile(fmus.path("pendulum_cvode_fmi3")) as archive:
        root = ElementTree.fromstring(archive.read("modelDescription.xml"))
    flags = {v.get("name"): v.get("intermediateUpdate") for v in root.iter("Float64")}
    assert flags["torque"] == "true"
    assert flags["theta"] is None


@pytest.mark.parametrize("name", ["pendulum_cvode_fmi3", "pendulum_euler_fmi3"])
def test_fmi3_intermediate_update_sets_inputs_inside_the_step(tmp_path, name):
    path = fmus.path(name)
    description = read_model_description(path)
    slave = FMU3Slave(guid=description.guid, unzipDirectory=extract(path, unzipdir=tmp_path),
                      modelIdentifier=description.coSimulation.modelIdentifier,
                      instanceName="p")
    variables = {v.name: v.valueReference for v in description.modelVariables}
    asked: list[float] = []

    def answer(environment, t, set_requested, get_allowed, finished, can_return_early,
               early_return_requested, early_return_time):
        assert set_requested
        asked.append(t)
        slave.setFloat64([variables["torque"]], [torque(t)])

    slave.instantiate(intermediateUpdate=answer,
                      requiredIntermediateVariables=[variables["torque"]])
    try:
        slave.enterInitializationMode(tolerance=1e-10)
        slave.setFloat64([variables["theta0"]], [THETA0])
        if name.startswith("pendulum_euler"):
            slave.setFloat64([variables["euler_step_size"]], [1e-5])
        slave.exitInitializationMode()
        slave.doStep(0.0, T_STEP)
        theta, _ = pendulum_reference(T_STEP, torque)
        bound = 1e-7 if "cvode" in name else 1e-4
        assert slave.getFloat64([variables["theta"]])[0] == pytest.approx(theta, abs=bound)
        assert asked and 0.0 <= min(asked) and max(asked) <= T_STEP
        d_theta, = slave.getOutputDerivatives([variables["theta"]], [1])
        assert d_theta == pytest.approx(slave.getFloat64([variables["omega"]])[0], rel=1e-8)
    finally:
        slave.terminate()
        slave.freeInstance()
