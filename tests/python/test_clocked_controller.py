"""The toolchain's clocked FMU (models/SampledPIController, FMI 3.0 only): a PI controller whose
output u is clocked by a periodic input clock. Driven here through FMPy's FMI 3.0 calls, the way
the standard lays out Co-Simulation with event mode: at each tick the importer enters Event
Mode, sets the inputs, ticks the clock (fmi3SetClock) and calls fmi3UpdateDiscreteStates."""

from __future__ import annotations

import ctypes
import math
import xml.etree.ElementTree as ElementTree
import zipfile
from collections.abc import Iterator

import numpy as np
import pytest
from fixture_fmus import fmu_path
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi3 import FMU3Slave
from fmpy.validation import validate_fmu
from scipy.integrate import solve_ivp
from syssimx import (
    Connection,
    EventConnection,
    FMUComponent,
    GaussSeidelAlgorithm,
    HybridAlgorithm,
    System,
    fmus,
)
from syssimx.system import SimulationResult
from syssimx.system.algorithms import Algorithm

CONTROLLER = "sampled_pi_controller_fmi3"
PERIOD = 0.1  # the clock's intervalDecimal
FMI3_ERROR = 3


class Slave:
    """An FMPy FMI 3.0 slave with its variables by name and the messages it logged."""

    def __init__(self, stem: str, directory, event_mode: bool) -> None:
        path = fmu_path(stem)
        description = read_model_description(path)
        self.vrs = {v.name: v.valueReference for v in description.modelVariables}
        self.slave = FMU3Slave(guid=description.guid,
                               unzipDirectory=extract(path, unzipdir=directory / stem),
                               modelIdentifier=description.coSimulation.modelIdentifier,
                               instanceName=stem)
        self.messages: list[str] = []

        def record(environment, status, category, message) -> None:
            self.messages.append(message.decode())

        self.slave.instantiate(loggingOn=True, eventModeUsed=event_mode,
                               earlyReturnAllowed=False, logMessage=record)

    def get(self, name: str) -> float:
        return self.slave.getFloat64([self.vrs[name]])[0]

    def set(self, name: str, value: float) -> None:
        self.slave.setFloat64([self.vrs[name]], [value])

    def initialize(self, starts: dict[str, float], tolerance: float | None = None) -> None:
        self.slave.enterInitializationMode(tolerance=tolerance, startTime=0.0)
        for name, value in starts.items():
            self.set(name, value)
        self.slave.exitInitializationMode()

    def step(self, t: float, dt: float) -> None:
        event_needed = self.slave.doStep(t, dt)[0]
        assert not event_needed

    def tick(self, inputs: dict[str, float]) -> None:
        """In Event Mode: set the inputs, tick the sample clock, update, back to Step Mode."""
        for name, value in inputs.items():
            self.set(name, value)
        self.slave.setClock([self.vrs["sample"]], [True])
        assert self.slave.updateDiscreteStates()[0] is False
        self.slave.enterStepMode()


@pytest.fixture
def slaves(tmp_path) -> Iterator[list[Slave]]:
    opened: list[Slave] = []
    yield opened
    for slave in opened:
        slave.slave.freeInstance()


def open_slave(slaves: list[Slave], tmp_path, stem: str, event_mode: bool) -> Slave:
    slaves.append(Slave(stem, tmp_path, event_mode))
    return slaves[-1]


def test_fmpy_validates_the_clocked_controller() -> None:
    assert validate_fmu(fmu_path(CONTROLLER)) == []


def test_the_description_declares_the_clock_and_the_clocked_output() -> None:
    with zipfile.ZipFile(fmu_path(CONTROLLER)) as archive:
        root = ElementTree.fromstring(archive.read("modelDescription.xml"))
    clock = root.find("ModelVariables/Clock").attrib
    assert (clock["name"], clock["causality"], clock["intervalVariability"]) == (
        "sample", "input", "constant")
    assert float(clock["intervalDecimal"]) == PERIOD
    clocked = {v.get("name") for v in root.find("ModelVariables")
               if v.get("clocks") == clock["valueReference"]}
    assert clocked == {"u", "integral"}
    assert root.find("CoSimulation").get("hasEventMode") == "true"


def test_u_changes_only_at_ticks_at_before_and_after_each(slaves, tmp_path) -> None:
    """The setpoint is a ramp set at every communication point, so a controller that followed
    its inputs between ticks would show it; u must stay at its tick's value until the next
    tick, be unchanged on entering Event Mode at the tick, and change only when the clock
    ticks."""
    kp, ki, eps = 2.0, 3.0, 1e-6
    fmu = open_slave(slaves, tmp_path, CONTROLLER, event_mode=True)
    fmu.initialize({"kp": kp, "ki": ki})
    integral, held = 0.0, 0.0
    t = 0.0
    for k in range(6):
        tick = k * PERIOD
        if k > 0:
            fmu.set("setpoint", tick - eps)  # just before the tick
            fmu.step(t, tick - eps - t)
            assert fmu.get("u") == held, f"u moved before the tick at {tick}"
            fmu.step(tick - eps, eps)
            fmu.slave.enterEventMode()
            assert fmu.get("u") == held, f"u moved on entering Event Mode at {tick}"
        error = tick - 0.25  # setpoint ramp, measurement 0.25
        fmu.tick({"setpoint": tick, "measurement": 0.25})
        held = kp * error + ki * integral
        assert fmu.get("u") == pytest.approx(held, abs=1e-15), f"u at the tick {tick}"
        held = fmu.get("u")
        integral += PERIOD * error
        fmu.set("setpoint", tick + 5.0)  # a jump just after the tick leaves u alone
        fmu.step(tick, eps)
        assert fmu.get("u") == held, f"u moved just after the tick at {tick}"
        t = tick + eps


def test_the_clock_s_interval_and_shift_are_read_in_initialization_mode(slaves,
                                                                         tmp_path) -> None:
    """An importer may ask a constant clock's interval and shift in Initialization Mode."""
    fmu = open_slave(slaves, tmp_path, CONTROLLER, event_mode=True)
    fmu.slave.enterInitializationMode(startTime=0.0)
    references = (ctypes.c_uint32 * 1)(fmu.vrs["sample"])
    intervals, qualifiers, shifts = (ctypes.c_double * 1)(), (ctypes.c_int * 1)(), \
        (ctypes.c_double * 1)()
    fmu.slave.getIntervalDecimal(references, intervals, qualifiers)
    fmu.slave.getShiftDecimal(references, shifts)
    assert (intervals[0], qualifiers[0], shifts[0]) == (PERIOD, 2, 0.0)  # fmi3IntervalChanged


def test_the_clock_ticks_in_event_mode_only_and_is_not_read(slaves, tmp_path) -> None:
    fmu = open_slave(slaves, tmp_path, CONTROLLER, event_mode=True)
    fmu.initialize({})
    fmu.slave.enterStepMode()
    with pytest.raises(FMICallException) as caught:
        fmu.slave.setClock([fmu.vrs["sample"]], [True])
    assert caught.value.status == FMI3_ERROR
    assert "Event Mode only" in fmu.messages[-1]
    with pytest.raises(FMICallException):
        fmu.slave.getClock([fmu.vrs["sample"]])
    assert "input clock" in fmu.messages[-1]


def pendulum_acceleration(theta: float, torque: float) -> float:
    """Pendulum.mo with its defaults: m = 40 kg, L = 0.6 m, g = 9.81 m/s2, inertia 20 kg m2."""
    return -(40.0 * 9.81 * 0.6 / 20.0) * math.sin(theta) + torque / 20.0


def sampled_data_reference(kp: float, ki: float, setpoint: float,
                           ticks: int) -> list[tuple[float, float]]:
    """theta and u at each tick: the PI law by hand, the pendulum by scipy's solve_ivp at tight
    tolerance between ticks, its torque held at the tick's u."""
    theta, omega, integral = 0.0, 0.0, 0.0
    samples = []
    for k in range(ticks):
        error = setpoint - theta
        u = kp * error + ki * integral
        integral += PERIOD * error
        samples.append((theta, u))
        solution = solve_ivp(lambda t, y, torque=u: [y[1], pendulum_acceleration(y[0], torque)],
                             (k * PERIOD, (k + 1) * PERIOD), [theta, omega], method="DOP853",
                             rtol=1e-12, atol=1e-14)
        theta, omega = solution.y[0, -1], solution.y[1, -1]
    return samples


def test_the_loop_with_the_pendulum_equals_the_sampled_data_reference(slaves, tmp_path) -> None:
    """The controller's u drives the pendulum's torque, theta its measurement, sampled every
    0.1 s for 3 s; the pendulum steps 10 times per sample period (CVODE at tolerance 1e-10)."""
    kp, ki, setpoint, ticks = 400.0, 200.0, 0.5, 30
    controller = open_slave(slaves, tmp_path, CONTROLLER, event_mode=True)
    pendulum = open_slave(slaves, tmp_path, "pendulum_cvode_fmi3", event_mode=False)
    controller.initialize({"kp": kp, "ki": ki})
    pendulum.initialize({}, tolerance=1e-10)
    samples = []
    for k in range(ticks):
        t = k * PERIOD
        if k > 0:
            controller.step(t - PERIOD, PERIOD)
            controller.slave.enterEventMode()
        theta = pendulum.get("theta")
        controller.tick({"setpoint": setpoint, "measurement": theta})
        samples.append((theta, controller.get("u")))
        pendulum.set("torque", controller.get("u"))
        for i in range(10):
            pendulum.step(t + i * PERIOD / 10, PERIOD / 10)
    reference = sampled_data_reference(kp, ki, setpoint, ticks)
    for k, ((theta, u), (theta_ref, u_ref)) in enumerate(zip(samples, reference, strict=True)):
        assert theta == pytest.approx(theta_ref, abs=1e-7), f"theta at tick {k}"
        assert u == pytest.approx(u_ref, abs=1e-4), f"u at tick {k}"
    # the loop does something: the pendulum swings towards the setpoint
    assert max(theta for theta, _ in samples) > 0.3


# ------------------------------------------------------------------ the engine ticks the clock
def closed_loop(dt: float, algorithm: Algorithm | None = None, tf: float = 3.0) -> SimulationResult:
    """sampled_pi_controller_fmi3 (kp 400, ki 200, setpoint 0.5) driving pendulum_cvode_fmi3's
    torque from its angle, run by syssimx with communication step dt."""
    controller = FMUComponent("PI", fmus.path(CONTROLLER))
    controller.set_parameters(kp=400.0, ki=200.0)
    controller.set_inputs({"setpoint": 0.5})
    pendulum = FMUComponent("P", fmus.path("pendulum_cvode_fmi3"), tolerance=1e-10)
    system = System("clocked loop")
    system.add_component(pendulum)
    system.add_component(controller)
    system.add_connection(Connection("P", "theta", "PI", "measurement"))
    system.add_connection(Connection("PI", "u", "P", "torque"))
    if algorithm is not None:
        system.set_algorithm(algorithm)
    system.initialize(0.0)
    return system.run(0.0, tf, dt)


def test_the_engine_ticks_the_clock_and_the_loop_equals_the_sampled_data_reference() -> None:
    """Gauss-Seidel steps the pendulum first: the controller ticks at each communication point
    with the angle there, as a sampled-data loop does."""
    result = closed_loop(PERIOD, GaussSeidelAlgorithm())
    t, pendulum = result["P"]
    _, controller = result["PI"]
    reference = sampled_data_reference(400.0, 200.0, 0.5, 30)
    on_ticks = [int(np.argmin(np.abs(t - k * PERIOD))) for k in range(30)]
    for k, i in enumerate(on_ticks):
        theta_ref, u_ref = reference[k]
        assert pendulum["theta"][i] == pytest.approx(theta_ref, abs=1e-7), f"theta at tick {k}"
        assert controller["u"][i] == pytest.approx(u_ref, abs=1e-4), f"u at tick {k}"
    ticks = [e for e in result.events if e.event == "clock_tick"]
    assert [round(e.t, 9) for e in ticks] == [round(k * PERIOD, 9) for k in range(1, 31)]


def test_ticks_inside_a_step_cut_only_the_clocked_fmu_s_step() -> None:
    """With a communication step of 0.25 s, the ticks at 0.1, 0.2, 0.3, ... fall inside steps:
    the controller's doStep ends at each and the tick is recorded there, while the system's
    grid stays 0, 0.25, 0.5, ... and u is held between ticks."""
    result = closed_loop(0.25, tf=1.0)
    t, _ = result["PI"]
    assert list(np.round(t, 9)) == [0.0, 0.25, 0.5, 0.75, 1.0]
    ticks = [round(e.t, 9) for e in result.events if e.event == "clock_tick"]
    assert ticks == [round(k * PERIOD, 9) for k in range(1, 11)]


def test_as_model_exchange_the_clocked_fmu_ticks_as_in_co_simulation() -> None:
    """The controller alone, its inputs held, dt = 0.25: as Model Exchange the engine stops
    at each tick like a time event; the ticks and the staircase of u are Co-Simulation's."""
    def alone(interface: str) -> tuple[list[float], list[float]]:
        controller = FMUComponent("PI", fmus.path(CONTROLLER), interface=interface)
        controller.set_inputs({"setpoint": 0.5, "measurement": 0.25})
        system = System(interface)
        system.add_component(controller)
        system.initialize(0.0)
        result = system.run(0.0, 1.0, 0.25)
        return ([e.t for e in result.events if e.event == "clock_tick"],
                result["PI"][1]["u"].tolist())

    ticks, u = alone("model-exchange")
    assert [round(t, 9) for t in ticks] == [round(k * PERIOD, 9) for k in range(1, 11)]
    assert (ticks, u) == alone("co-simulation")
    # kp = ki = 1, e = 0.25 at every tick: u_k = e + T k e at tick k
    assert u == pytest.approx([0.25 * (1 + PERIOD * math.floor(t / PERIOD + 1e-9))
                               for t in (0.0, 0.25, 0.5, 0.75, 1.0)], rel=1e-12)


# ------------------------------------------------------------------ ticks as hybrid events
def ticks_and_peak(threads: int = 1) -> tuple[list[tuple[float, int, str, str]], list[float]]:
    """The clocked loop at dt = 0.25 under the hybrid algorithm, with an indicator on the
    pendulum's omega (its first peak, falling through zero, located by rollback inside a step
    that also holds clock ticks), one on the controller's u (which falls below zero at the tick
    of 0.4 s: a crossing at a tick's instant) and a Python listener of the controller's
    ticks."""
    controller = FMUComponent("PI", fmus.path(CONTROLLER))
    controller.set_parameters(kp=400.0, ki=200.0)
    controller.set_inputs({"setpoint": 0.5})
    heard: list[float] = []
    controller.add_event_handler("sampled", lambda _c, _names, t: heard.append(t))
    controller.add_event_indicator("braking", variable="u", direction=-1)
    controller.add_event_handler("braked", lambda *_: None)
    pendulum = FMUComponent("P", fmus.path("pendulum_cvode_fmi3"), tolerance=1e-10)
    pendulum.add_event_indicator("peak", variable="omega", direction=-1)
    pendulum.add_event_handler("peaked", lambda *_: None)
    system = System("ticks and a peak")
    system.add_component(pendulum)
    system.add_component(controller)
    system.add_connection(Connection("P", "theta", "PI", "measurement"))
    system.add_connection(Connection("PI", "u", "P", "torque"))
    system.add_event_connection(EventConnection.own_events("PI", "PI", "sampled"))
    system.add_event_connection(EventConnection("P", "peak", "P", "peaked"))
    system.add_event_connection(EventConnection("PI", "braking", "PI", "braked"))
    system.set_algorithm(HybridAlgorithm(tol_time=1e-10,
                                         coupling=GaussSeidelAlgorithm(threads=threads)))
    system.initialize(0.0)
    events = system.run(0.0, 1.0, 0.25).events
    return [(e.t, e.micro, e.component, e.event) for e in events], heard


def test_ticks_and_an_indicator_in_one_step_are_recorded_in_superdense_order() -> None:
    records, heard = ticks_and_peak()
    peaks = [r for r in records if r[3] == "peak"]
    ticks = [r for r in records if r[3] == "clock_tick"]
    assert len(peaks) == 1 and [round(r[0], 9) for r in ticks] == [
        round(k * PERIOD, 9) for k in range(1, 11)]
    # u jumps below zero at the tick of 0.4: the crossing is located there (within tol_time)
    # and recorded at the tick's instant, after the tick that caused it
    braking = records.index(next(r for r in records if r[3] == "braking"))
    assert records[braking - 1][3] == "clock_tick"
    assert records[braking - 1][:2] == records[braking][:2]
    assert records[braking][0] == pytest.approx(0.4, abs=1e-10)
    # the peak lies inside a communication step that also holds ticks
    step = math.floor(peaks[0][0] / 0.25)
    assert any(step * 0.25 < r[0] < (step + 1) * 0.25 for r in ticks)
    assert records == sorted(records, key=lambda r: (r[0], r[1]))
    assert heard == [r[0] for r in ticks]  # the listener ran at each tick, in order
    # the same records in every run and on two threads
    assert ticks_and_peak() == (records, heard)
    assert ticks_and_peak(threads=2) == (records, heard)
