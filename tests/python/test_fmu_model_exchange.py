"""Every bundled FMU is also an FMI 2.0 Model Exchange FMU (same binary, same modelIdentifier):
fmpy integrates its equations with CVODE and gets the exact pendulum and bouncing ball, and the
FMU keeps FMI 2.0's Model Exchange state machine, time events and FMU states."""

from __future__ import annotations

import ctypes
import re
import subprocess
import sys
from collections.abc import Iterator
from dataclasses import dataclass, field

import fmpy
import numpy as np
import pytest
from fixture_fmus import fmu_path
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Model, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE
from scipy.special import ellipj, ellipk
from test_fmu_bouncing_ball import H0, E, G, closed_form_bounces
from test_fmu_validation import BUILT

# the seed's pendulum: theta(t) from sin(theta / 2) = k sn(K - w t | k^2), theta(0) = THETA0
THETA0, M, L, INERTIA = 0.5, 40.0, 0.6, 20.0
W = np.sqrt(M * G * L / INERTIA)
K_MODULUS = np.sin(THETA0 / 2)
QUARTER_PERIOD = ellipk(K_MODULUS**2) / W
TOLERANCE = 1e-10


def exact_theta(t: np.ndarray) -> np.ndarray:
    sn = ellipj(ellipk(K_MODULUS**2) - W * t, K_MODULUS**2)[0]
    return 2 * np.arcsin(K_MODULUS * sn)


def simulate_me(name: str, **options) -> np.ndarray:
    return fmpy.simulate_fmu(fmu_path(name), fmi_type="ModelExchange", solver="CVode", **options)


@pytest.mark.parametrize("name", BUILT)
def test_model_exchange_is_declared_beside_co_simulation(name: str) -> None:
    description = read_model_description(fmu_path(name))
    me, cs = description.modelExchange, description.coSimulation
    assert me.modelIdentifier == cs.modelIdentifier == name
    assert me.canGetAndSetFMUstate and me.canSerializeFMUstate
    assert me.providesDirectionalDerivative == cs.providesDirectionalDerivative
    assert not me.needsCompletedIntegratorStep
    # every derivative variable is in ModelStructure's Derivatives, with its dependencies
    declared = {v.name for v in description.modelVariables if v.derivative is not None}
    assert {u.variable.name for u in description.derivatives} == declared
    assert all(u.dependencies is not None for u in description.derivatives)


@pytest.mark.parametrize(("name", "states"), [
    ("pendulum_cvode", ["theta", "omega"]),
    ("pendulum_contact_euler", ["theta", "omega"]),
    ("pi_controller", ["integral"]),
    ("sliding_mass", ["x", "v"]),
    ("sample_hold", []),
])
def test_the_state_vector_is_the_models(name: str, states: list[str]) -> None:
    description = read_model_description(fmu_path(name))
    assert [u.variable.derivative.name for u in description.derivatives] == states


def test_bouncing_ball_structure_for_model_exchange() -> None:
    description = read_model_description(fmu_path("bouncing_ball_cvode"))
    assert description.numberOfEventIndicators == 1
    assert description.numberOfContinuousStates == 2
    derivatives = {u.variable.name: (u.variable.derivative.name, [d.name for d in u.dependencies])
                   for u in description.derivatives}
    assert derivatives == {"der(h)": ("h", ["h", "v"]), "der(v)": ("v", ["h", "v"])}


@pytest.mark.parametrize("name", [n for n in BUILT if n != "failing"])
def test_every_fmu_runs_as_model_exchange(name: str) -> None:
    result = simulate_me(name, stop_time=1.0, output_interval=0.01)
    assert result["time"][-1] == pytest.approx(1.0, abs=1e-12)


# FMPy keeps a logger it was given after simulate_fmu raises, and a later FMU's message calls the
# freed callback: the failing run goes in a process of its own.
FAILING_RUN = """
import fmpy, sys
messages = []
def record(environment, instance, status, category, message):
    messages.append(message.decode())
try:
    fmpy.simulate_fmu(sys.argv[1], fmi_type="ModelExchange", solver="CVode", stop_time=1.0,
                      output_interval=0.1, logger=record, start_values={"fail_time": 0.5})
except RuntimeError as error:
    print("raised:", error)
print("\\n".join("message: " + m for m in messages))
"""


# fmi2SetTime fails inside FMPy's right-hand side callback, which can only print the exception;
# CVODE then gives up
def test_failing_fmu_refuses_the_time_past_fail_time() -> None:
    run = subprocess.run([sys.executable, "-c", FAILING_RUN, str(fmu_path("failing"))],
                         capture_output=True, text=True, timeout=120, check=True)
    # FMPy's CVODE prints its own warnings to the same output
    lines = run.stdout.splitlines()
    raised = [line for line in lines if line.startswith("raised: ")]
    assert len(raised) == 1 and "the right-hand side routine failed" in raised[0]
    messages = [line.removeprefix("message: ") for line in lines if line.startswith("message: ")]
    refused = [re.fullmatch(r"fmi2SetTime to t = (\S+): the simulation passed fail_time "
                            r"\(a deliberate failure\)", m) for m in messages]
    assert refused and all(refused)
    assert all(float(match.group(1)) > 0.5 for match in refused)


def test_pendulum_follows_the_exact_solution() -> None:
    # CVODE keeps every local error within TOLERANCE (states of order one, nominal 1): over the
    # 1 s run, about two quarter periods, the global error stays within 10x (issue 16's bound)
    me = simulate_me("pendulum_cvode", relative_tolerance=TOLERANCE, stop_time=1.0,
                     output_interval=0.01, start_values={"theta0": THETA0})
    assert np.abs(me["theta"] - exact_theta(me["time"])).max() < 10 * TOLERANCE
    # the importer integrates: the Euler build serves the same equations, to the last bit
    euler = simulate_me("pendulum_euler", relative_tolerance=TOLERANCE, stop_time=1.0,
                        output_interval=0.01, start_values={"theta0": THETA0})
    assert np.array_equal(euler["theta"], me["theta"])
    quarter = simulate_me("pendulum_cvode", relative_tolerance=TOLERANCE,
                          stop_time=QUARTER_PERIOD, output_interval=QUARTER_PERIOD / 4,
                          start_values={"theta0": THETA0})
    assert quarter["time"][-1] == QUARTER_PERIOD
    assert abs(quarter["theta"][-1]) < 10 * TOLERANCE
    # the co-simulation build integrates the same equations with its own CVODE: both within
    # 10x of the exact solution, so within 20x of each other
    cs = fmpy.simulate_fmu(fmu_path("pendulum_cvode"), stop_time=1.0, output_interval=0.01,
                           start_values={"theta0": THETA0, "cvode_relative_tolerance": TOLERANCE})
    assert np.array_equal(cs["time"], me["time"])
    assert np.abs(me["theta"] - cs["theta"]).max() < 20 * TOLERANCE


def test_bouncing_ball_bounces_at_the_closed_form_times() -> None:
    result = simulate_me("bouncing_ball_cvode", relative_tolerance=TOLERANCE, stop_time=3.0,
                         output_interval=0.01, record_events=True)
    t, v = result["time"], result["v"]
    # an event is recorded twice at one time: before (falling) and after handling (rising)
    before = np.flatnonzero((t[1:] == t[:-1]) & (v[:-1] < 0) & (v[1:] > 0))
    expected = closed_form_bounces(len(before))
    assert len(before) == 6  # the seventh bounce is at 3.04 s
    # FMPy's CVODE locates each root of h; the error is CVODE's, accumulated over the flights
    assert np.abs(t[before] - expected).max() < 1e-8
    impact = np.sqrt(2 * G * H0) * E ** np.arange(len(before))
    assert np.abs(v[before] + impact).max() < 1e-8
    assert np.array_equal(v[before + 1], -E * v[before])
    assert np.all(result["h"][before + 1] == 0.0)


# ------------------------------------------------------------------ direct calls through fmpy
@dataclass
class OpenModel:
    model: FMU2Model
    n_states: int
    n_indicators: int
    vrs: dict[str, int]
    messages: list[str] = field(default_factory=list)
    callbacks: fmi2CallbackFunctions | None = None  # keeps fmpy's logger callback alive

    def states(self) -> list[float]:
        x = (ctypes.c_double * self.n_states)()
        self.model.getContinuousStates(x, self.n_states)
        return list(x)

    def set_states(self, values: list[float]) -> None:
        self.model.setContinuousStates((ctypes.c_double * self.n_states)(*values), self.n_states)

    def derivatives(self) -> list[float]:
        dx = (ctypes.c_double * self.n_states)()
        self.model.getDerivatives(dx, self.n_states)
        return list(dx)

    def indicators(self) -> list[float]:
        z = (ctypes.c_double * self.n_indicators)()
        self.model.getEventIndicators(z, self.n_indicators)
        return list(z)

    def refused(self, call, *args) -> str:
        """The message of a call that must fail with fmi2Error."""
        with pytest.raises(FMICallException) as caught:
            call(*args)
        assert caught.value.status == 3
        return self.messages[-1]


@pytest.fixture
def open_model(tmp_path) -> Iterator:
    """open_model(name, starts) instantiates a bundled FMU as Model Exchange and initializes it:
    the model is then in event mode at t = 0."""
    opened: list[OpenModel] = []

    def open_one(name: str, starts: dict[str, float] | None = None) -> OpenModel:
        description = read_model_description(fmu_path(name))
        unzipped = fmpy.extract(fmu_path(name), unzipdir=tmp_path / f"me-{name}-{len(opened)}")
        model = FMU2Model(guid=description.guid, unzipDirectory=unzipped,
                          modelIdentifier=description.modelExchange.modelIdentifier,
                          instanceName=name)
        vrs = {v.name: v.valueReference for v in description.modelVariables}
        opened.append(OpenModel(model, description.numberOfContinuousStates,
                                description.numberOfEventIndicators, vrs))
        handle = opened[-1]
        handle.callbacks = fmi2CallbackFunctions()
        handle.callbacks.logger = fmi2CallbackLoggerTYPE(
            lambda env, instance, status, category, message: handle.messages.append(
                message.decode()))
        model.instantiate(callbacks=handle.callbacks, loggingOn=True)
        model.setupExperiment(startTime=0.0)
        model.enterInitializationMode()
        for variable, value in (starts or {}).items():
            model.setReal([vrs[variable]], [value])
        model.exitInitializationMode()
        return handle

    yield open_one
    for handle in opened:
        handle.model.freeInstance()


def test_wrong_state_calls_fail_with_a_message(open_model) -> None:
    ball = open_model("bouncing_ball_cvode")
    m = ball.model
    assert ball.refused(ball.set_states, [1.0, 0.0]) == (
        "fmi2SetContinuousStates is not allowed in event mode")
    assert ball.refused(m.completedIntegratorStep) == (
        "fmi2CompletedIntegratorStep is not allowed in event mode")
    do_step = m.dll.fmi2DoStep  # not in fmpy's FMU2Model: called as the binary exports it
    do_step.argtypes = [ctypes.c_void_p, ctypes.c_double, ctypes.c_double, ctypes.c_int]
    assert do_step(m.component, 0.0, 0.1, 1) == 3
    assert ball.messages[-1] == "fmi2DoStep is not allowed in event mode"
    m.newDiscreteStates()
    m.enterContinuousTimeMode()
    assert ball.refused(m.newDiscreteStates) == (
        "fmi2NewDiscreteStates is not allowed in continuous-time mode")
    assert ball.refused(m.enterContinuousTimeMode) == (
        "fmi2EnterContinuousTimeMode is not allowed in continuous-time mode")
    assert ball.refused(m.setReal, [ball.vrs["g"]], [1.0]) == (
        "fmi2SetReal: g is a fixed parameter and cannot be changed in continuous-time mode "
        "(set it before fmi2ExitInitializationMode, or use fmi2Reset)")
    m.terminate()
    assert ball.refused(m.setTime, 1.0) == "fmi2SetTime is not allowed in terminated"
    m.reset()
    assert ball.refused(m.enterEventMode) == "fmi2EnterEventMode is not allowed in instantiated"
    assert ball.refused(m.getDerivatives, (ctypes.c_double * 2)(), 2) == (
        "fmi2GetDerivatives is not allowed in instantiated")


def test_vector_lengths_are_checked(open_model) -> None:
    ball = open_model("bouncing_ball_cvode")
    assert ball.refused(ball.model.getEventIndicators, (ctypes.c_double * 2)(), 2) == (
        "fmi2GetEventIndicators: 2 event indicators requested, the model has 1")


def test_bounce_in_event_mode(open_model) -> None:
    ball = open_model("bouncing_ball_cvode", {"h0": 0.5, "v0": 1.0})
    m = ball.model
    assert ball.states() == [0.5, 1.0]
    assert ball.derivatives() == [1.0, -9.81]
    assert m.newDiscreteStates() == (False, False, False, False, False, 0.0)
    m.enterContinuousTimeMode()
    ball.set_states([1e-3, -2.0])
    m.setTime(0.6)
    assert ball.indicators() == [1e-3]
    ball.set_states([-1e-12, -3.0])  # the root finder's point just past the floor
    assert ball.indicators() == [-1e-12]
    m.enterEventMode()
    assert m.newDiscreteStates() == (False, False, False, True, False, 0.0)
    assert ball.states() == [0.0, 0.8 * 3.0]
    # a second pass changes nothing: the event was handled
    assert m.newDiscreteStates() == (False, False, False, False, False, 0.0)
    # h = 0 after the bounce: the next fall fires once the ball was seen above the floor
    m.enterContinuousTimeMode()
    ball.set_states([-1e-12, -2.4])
    m.enterEventMode()
    assert m.newDiscreteStates()[3] is False
    m.enterContinuousTimeMode()
    ball.set_states([0.1, 1.0])
    assert ball.indicators() == [0.1]
    ball.set_states([-1e-12, -2.4])
    m.enterEventMode()
    assert m.newDiscreteStates()[3] is True
    assert ball.states() == [0.0, 0.8 * 2.4]


def test_time_events_and_termination(open_model) -> None:
    sampler = open_model("sample_hold", {"hold_step": 0.25})
    assert sampler.model.newDiscreteStates()[4:] == (True, 0.25)
    sampler.model.enterContinuousTimeMode()
    sampler.model.setTime(0.25)
    sampler.model.enterEventMode()
    assert sampler.model.newDiscreteStates()[4:] == (True, 0.5)
    assert sampler.model.getReal([sampler.vrs["y"]]) == [np.cos(2 * np.pi * 0.7 * 0.25)]

    ramp = open_model("terminating", {"stop_time": 0.75})
    assert ramp.model.newDiscreteStates() == (False, False, False, False, True, 0.75)
    ramp.model.enterContinuousTimeMode()
    assert ramp.model.completedIntegratorStep() == (False, False)
    ramp.model.setTime(0.75)
    assert ramp.model.completedIntegratorStep() == (False, True)
    ramp.model.enterEventMode()
    assert ramp.model.newDiscreteStates()[:2] == (False, True)


def test_fmu_state_restores_the_mode_the_states_and_the_armed_indicator(
        open_model, open_fmu) -> None:
    ball = open_model("bouncing_ball_cvode")
    m = ball.model
    m.newDiscreteStates()
    m.enterContinuousTimeMode()
    m.setTime(0.4)
    ball.set_states([0.2, -3.9])
    assert ball.indicators() == [0.2]  # arms the fall
    state = m.getFMUState()
    serialized = m.serializeFMUState(state)

    def bounce() -> tuple[bool, list[float]]:
        ball.set_states([-1e-12, -4.4])
        m.enterEventMode()
        changed = m.newDiscreteStates()[3]
        return changed, ball.states()

    first = bounce()
    assert first == (True, [0.0, 0.8 * 4.4])
    m.setFMUState(state)  # continuous-time mode again, the fall still armed
    assert ball.states() == [0.2, -3.9]
    assert bounce() == first
    copy = m.deserializeFMUState(serialized)
    m.setFMUState(copy)
    assert bounce() == first
    m.freeFMUState(copy)
    m.freeFMUState(state)

    # a running state belongs to its interface: a co-simulation state is refused
    slave = open_fmu("bouncing_ball_cvode").slave
    slave_state = slave.getFMUState()
    foreign = slave.serializeFMUState(slave_state)
    slave.freeFMUState(slave_state)
    assert ball.refused(m.deserializeFMUState, foreign) == (
        "fmi2DeSerializeFMUstate: the bytes are not a state of this FMU")
