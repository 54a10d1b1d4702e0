"""The FMI 3.0 builds of every model (stem_fmi3.fmu), checked through FMPy, an FMI 3.0 client
independent of syssimx: valid modelDescriptions, the FMI 2.0 build's results, early return at
internal events with event mode, FMU state round trips, the state machine's refusals, and the
Model Exchange interface beside Co-Simulation."""

from __future__ import annotations

import math
import re
import subprocess
import xml.etree.ElementTree as ElementTree
import zipfile
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

import fmpy
import numpy as np
import pytest
from fixture_fmus import FIXTURES, fmu_path
from fmpy import extract, read_model_description
from fmpy.fmi3 import FMU3Slave
from fmpy.model_description import ModelVariable
from fmpy.validation import validate_fmu
from syssimx import fmus

# the one list of the bundled FMUs: the stems of models/meson.build's fmu_builds
FMU_BUILDS = re.search(r"^fmu_builds = \[\n(.*?)^\]", (
    Path(__file__).resolve().parents[2] / "models" / "meson.build").read_text(), re.M | re.S)
BUILT = re.findall(r"^\s*\['(\w+)',", FMU_BUILDS.group(1), re.M) if FMU_BUILDS else []
SHIPPED = BUILT
BUILT = [*SHIPPED, *FIXTURES]  # the toolchain builds the test fixtures the same way

# fmi3Functions.h declares 75 functions; an FMI 3.0 FMU exports all of them and nothing else
FMI3_FUNCTION_COUNT = 75


@dataclass
class OpenFMU3:
    """An FMPy FMI 3.0 slave of a bundled FMU, its variables by name and the messages it logged."""

    slave: FMU3Slave
    variables: dict[str, ModelVariable]
    messages: list[tuple[int, str]] = field(default_factory=list)

    def vr(self, name: str) -> int:
        return self.variables[name].valueReference

    def get(self, name: str) -> float:
        return self.slave.getFloat64([self.vr(name)])[0]

    def set(self, name: str, value: float) -> None:
        variable = self.variables[name]
        if variable.type == "Int32":
            self.slave.setInt32([variable.valueReference], [int(value)])
        else:
            self.slave.setFloat64([variable.valueReference], [float(value)])

    def refused(self, call: Callable[..., object], *args: object) -> str:
        """Calls what must fail with fmi3Error and returns the FMU's last message."""
        with pytest.raises(fmpy.fmi1.FMICallException) as caught:
            call(*args)
        assert caught.value.status == 3  # fmi3Error
        return self.messages[-1][1]


@pytest.fixture
def open_fmu3(tmp_path) -> Iterator[Callable[..., OpenFMU3]]:
    """open_fmu3(stem, starts={...}, tolerance=None, event_mode=False, initialize=True)
    instantiates stem_fmi3 (event mode and early return both as `event_mode`), enters and leaves
    initialization with the start values, and leaves the FMU in Step Mode (with event mode, after
    the initial discrete update). Instances are freed after the test."""
    opened: list[OpenFMU3] = []

    def open_one(stem: str, starts: dict[str, float] | None = None,
                 tolerance: float | None = None, event_mode: bool = False,
                 initialize: bool = True) -> OpenFMU3:
        path = fmu_path(stem + "_fmi3")
        description = read_model_description(path)
        slave = FMU3Slave(guid=description.guid,
                          unzipDirectory=extract(path, unzipdir=tmp_path / f"{stem}-{len(opened)}"),
                          modelIdentifier=description.coSimulation.modelIdentifier,
                          instanceName=stem)
        fmu = OpenFMU3(slave, {v.name: v for v in description.modelVariables})

        def record(environment, status, category, message) -> None:
            fmu.messages.append((status, message.decode()))

        slave.instantiate(loggingOn=True, eventModeUsed=event_mode, earlyReturnAllowed=event_mode,
                          logMessage=record)
        opened.append(fmu)
        if initialize:
            slave.enterInitializationMode(tolerance=tolerance, startTime=0.0)
            for name, value in (starts or {}).items():
                fmu.set(name, value)
            slave.exitInitializationMode()
            if event_mode:
                assert slave.updateDiscreteStates()[0] is False
                slave.enterStepMode()
        return fmu

    yield open_one
    for fmu in opened:
        fmu.slave.freeInstance()


def co_simulation_attributes(stem: str) -> dict[str, str]:
    """The attributes of <CoSimulation> as written (FMPy renames FMI 3.0's capability flags)."""
    with zipfile.ZipFile(fmu_path(stem + "_fmi3")) as archive:
        root = ElementTree.fromstring(archive.read("modelDescription.xml"))
    return dict(root.find("CoSimulation").attrib)


# ------------------------------------------------------------------------------ the builds
def test_every_model_has_an_fmi3_build() -> None:
    assert SHIPPED, "no fmu_builds list found in models/meson.build"
    assert {stem + "_fmi3" for stem in SHIPPED} <= set(fmus.available())


@pytest.mark.parametrize("stem", BUILT)
def test_fmpy_finds_no_problem(stem: str) -> None:
    assert validate_fmu(fmu_path(stem + "_fmi3")) == []


@pytest.mark.parametrize("stem", BUILT)
def test_description_declares_the_fmi3_interface(stem: str) -> None:
    fmi2 = read_model_description(fmu_path(stem))
    fmi3 = read_model_description(fmu_path(stem + "_fmi3"))
    assert fmi3.fmiVersion == "3.0"
    assert fmi3.coSimulation.modelIdentifier == stem + "_fmi3"
    assert fmi3.guid == fmi2.guid  # the instantiationToken is the model's GUID
    flags = co_simulation_attributes(stem)
    assert flags["canGetAndSetFMUState"] == flags["canSerializeFMUState"] == "true"
    assert flags.get("providesDirectionalDerivatives", "false") == \
        str(fmi2.coSimulation.providesDirectionalDerivative).lower()
    experiment = fmi3.defaultExperiment
    assert (experiment.stopTime, experiment.stepSize) == \
        (fmi2.defaultExperiment.stopTime, fmi2.defaultExperiment.stepSize)
    # the same variables under the same value references, with their units and base units
    by_vr = {v.valueReference: v for v in fmi3.modelVariables}
    for variable in fmi2.modelVariables:
        twin = by_vr[variable.valueReference]
        assert (twin.name, twin.causality, twin.unit) == \
            (variable.name, variable.causality, variable.unit)
        assert twin.type == {"Real": "Float64", "Integer": "Int32"}.get(variable.type,
                                                                          variable.type)
    assert [(u.name, u.baseUnit.m, u.baseUnit.s) for u in fmi3.unitDefinitions] == \
        [(u.name, u.baseUnit.m, u.baseUnit.s) for u in fmi2.unitDefinitions]
    assert [u.variable.name for u in fmi3.outputs] == [u.variable.name for u in fmi2.outputs]
    assert [u.variable.name for u in fmi3.derivatives] == \
        [u.variable.name for u in fmi2.derivatives]
    assert [u.variable.name for u in fmi3.initialUnknowns] == \
        [u.variable.name for u in fmi2.initialUnknowns]


def test_internal_events_declare_event_mode_and_early_return() -> None:
    with_events = {"bouncing_ball_euler", "bouncing_ball_cvode", "pendulum_contact_euler",
                   "pendulum_contact_cvode", "sliding_mass", "hostile_ball"}
    for stem in BUILT:
        description = read_model_description(fmu_path(stem + "_fmi3"))
        flags = co_simulation_attributes(stem)
        events = stem in with_events
        assert flags.get("hasEventMode", "false") == str(events).lower(), stem
        assert flags.get("canReturnEarlyAfterIntermediateUpdate", "false") == \
            str(events).lower(), stem
        # inputs move inside a step through intermediate update (test_fmu_interpolation.py)
        assert flags.get("providesIntermediateUpdate") == "true", stem
        assert len(description.eventIndicators) == int(events), stem
        assert flags.get("mightReturnEarlyFromDoStep", "false") == \
            str(events or stem == "terminating").lower(), stem
    ball = read_model_description(fmu_path("bouncing_ball_cvode_fmi3"))
    assert ball.eventIndicators[0].variable.name == "event_indicator_0"
    assert [v.name for v in ball.modelVariables if v.causality == "independent"] == ["time"]


@pytest.mark.parametrize("stem", ["pendulum_euler", "pendulum_cvode", "bouncing_ball_cvode"])
def test_binary_exports_only_fmi3_and_needs_only_libc_and_libm(stem: str, tmp_path) -> None:
    unzipped = extract(fmu_path(stem + "_fmi3"), unzipdir=tmp_path / stem)
    binary = f"{unzipped}/binaries/x86_64-linux/{stem}_fmi3.so"
    symbols = subprocess.run(
        ["nm", "-D", "--defined-only", binary], check=True, capture_output=True, text=True
    ).stdout.split()
    exported = [s for s in symbols if len(s) > 1 and s[0].isalpha() and not s.isupper()]
    assert len(exported) == FMI3_FUNCTION_COUNT
    assert all(s.startswith("fmi3") for s in exported)
    dynamic = subprocess.run(
        ["readelf", "-d", binary], check=True, capture_output=True, text=True
    ).stdout
    needed = {line.split("[")[1].rstrip("]") for line in dynamic.splitlines() if "(NEEDED)" in line}
    assert needed <= {"libc.so.6", "libm.so.6"}


# ------------------------------------------------------------------------------ results
@pytest.mark.parametrize("stem", BUILT)
def test_simulate_fmu_gives_the_fmi2_results(stem: str) -> None:
    """Over the DefaultExperiment, FMPy gets the very numbers of the FMI 2.0 build (Euler and
    CVODE alike: the same model and back-end code runs). terminating asks to stop at t = 1:
    FMI 2.0 says so with a discarded step, FMI 3.0 with terminateSimulation and an early return
    at the stop time."""
    fmi2 = fmpy.simulate_fmu(fmu_path(stem))
    fmi3 = fmpy.simulate_fmu(fmu_path(stem + "_fmi3"), early_return_allowed=True)
    assert fmi3.dtype.names == fmi2.dtype.names
    assert len(fmi3) == len(fmi2) > 10
    for name in fmi2.dtype.names:
        np.testing.assert_array_equal(fmi3[name], fmi2[name], err_msg=name)


def test_with_event_mode_the_results_are_those_of_internal_handling() -> None:
    """Events applied by the importer at the returned time continue the trajectory exactly as
    the FMU's own handling does: the grid samples of both runs are identical."""
    path = fmu_path("bouncing_ball_cvode_fmi3")
    internal = fmpy.simulate_fmu(path, relative_tolerance=1e-10)
    external = fmpy.simulate_fmu(path, relative_tolerance=1e-10, use_event_mode=True,
                                 early_return_allowed=True)
    on_grid = np.isin(external["time"], internal["time"])
    # the event instants appear twice (before and after the update); the rest is the grid
    assert np.count_nonzero(~on_grid) == 2 * 6
    np.testing.assert_array_equal(external["time"][on_grid], internal["time"])
    np.testing.assert_array_equal(external["h"][on_grid], internal["h"])
    np.testing.assert_array_equal(external["v"][on_grid], internal["v"])


# ------------------------------------------------------------------------------ early return
G, E, H0 = 9.81, 0.8, 1.0


def closed_form_bounces(t_end: float) -> list[float]:
    """Bounce times of the ideal ball: the fall sqrt(2 h0 / g), then flights 2 e^k v1 / g."""
    v1 = math.sqrt(2.0 * G * H0)
    times = [math.sqrt(2.0 * H0 / G)]
    k = 1
    while times[-1] + 2.0 * E**k * v1 / G < t_end:
        times.append(times[-1] + 2.0 * E**k * v1 / G)
        k += 1
    return times


def run_with_event_mode(fmu: OpenFMU3, t_end: float, dt: float) -> list[tuple[float, float, float]]:
    """Steps over the grid k dt up to t_end, handling each early return in Event Mode and going
    on to the same grid point; (time, v before, v after) per event."""
    events = []
    t, k = 0.0, 0
    while k * dt < t_end - 1e-12:
        grid_point = k * dt + dt  # as the FMI 2.0 run steps: doStep(k dt, dt)
        needed, terminate, early, t_last = fmu.slave.doStep(t, grid_point - t)
        assert not terminate
        assert early is (t_last < grid_point)
        t = t_last
        k += not early
        if needed:
            before = fmu.get("v")
            fmu.slave.enterEventMode()
            update = fmu.slave.updateDiscreteStates()
            # needs no update, no termination, no nominals changed, states changed, no time event
            assert update[:5] == (False, False, False, True, False)
            fmu.slave.enterStepMode()
            events.append((t, before, fmu.get("v")))
    return events


def test_cvode_returns_early_at_each_bounce(open_fmu3) -> None:
    fmu = open_fmu3("bouncing_ball_cvode", tolerance=1e-10, event_mode=True)
    events = run_with_event_mode(fmu, 3.0, 0.01)
    exact = closed_form_bounces(3.0)
    assert len(events) == len(exact) == 6
    for (t, before, after), t_exact in zip(events, exact, strict=True):
        assert t == pytest.approx(t_exact, abs=1e-8)
        assert after == pytest.approx(-E * before, rel=1e-15)
        assert before < 0.0


def test_early_return_times_are_the_fmi2_builds_internal_event_times(open_fmu,
                                                                    open_fmu3) -> None:
    """The FMI 2.0 build logs each internal event it handles; the FMI 3.0 build returns at
    exactly those times: CVODE at the root it found, Euler at the point it located by linear
    interpolation inside the Euler substep where the height crossed zero."""
    for stem in ("bouncing_ball_cvode", "bouncing_ball_euler"):
        fmi2 = open_fmu(stem, tolerance=1e-10)
        for k in range(300):
            fmi2.slave.doStep(k * 0.01, 0.01)
        logged = [float(m.split("t = ")[1]) for _, m in fmi2.messages if "internal event" in m]
        assert len(logged) == 6, stem
        events = run_with_event_mode(open_fmu3(stem, tolerance=1e-10, event_mode=True), 3.0, 0.01)
        assert [t for t, _, _ in events] == logged, stem


def test_euler_stops_at_the_located_crossing(open_fmu3) -> None:
    fmu = open_fmu3("bouncing_ball_euler", event_mode=True)
    t = 0.0
    while True:
        needed, _, early, t_last = fmu.slave.doStep(t, 0.01)
        if needed:
            break
        t = t_last
    exact = closed_form_bounces(1.0)[0]
    # inside the step where it crossed, on the floor, still falling
    assert early and t < t_last < t + 0.01
    assert t_last == pytest.approx(exact, abs=1e-3)
    assert fmu.get("h") == pytest.approx(0.0, abs=1e-15)
    assert fmu.get("v") < 0.0
    assert fmu.slave.getFloat64([fmu.vr("event_indicator_0")])[0] == fmu.get("h")


# ------------------------------------------------------------------------------ FMU states
def steps(fmu: OpenFMU3, t_from: float, t_to: float, dt: float = 0.01) -> tuple[float, float]:
    for k in range(round((t_to - t_from) / dt)):
        fmu.slave.doStep(t_from + k * dt, dt)
    return fmu.get("theta"), fmu.get("omega")


@pytest.mark.parametrize(("stem", "relative"), [
    ("pendulum_euler", 0.0),  # the same arithmetic again: bit-identical
    ("pendulum_cvode", 1e-9),  # CVODE restarts at t1, agreeing to its tolerance 1e-10
])
def test_state_round_trip_reproduces_the_next_steps(open_fmu3, stem: str,
                                                    relative: float) -> None:
    tolerance = 1e-10 if stem.endswith("cvode") else None
    fmu = open_fmu3(stem, starts={"theta0": 0.5}, tolerance=tolerance)
    steps(fmu, 0.0, 0.2)
    state = fmu.slave.getFMUState()
    first = steps(fmu, 0.2, 0.7)
    fmu.slave.setFMUState(state)
    second = steps(fmu, 0.2, 0.7)
    assert second == pytest.approx(first, rel=relative, abs=0.0)
    fmu.slave.setFMUState(state)
    assert steps(fmu, 0.2, 0.7) == second  # a restored state replays bit for bit

    serialized = fmu.slave.serializeFMUState(state)
    fresh = open_fmu3(stem, starts={"theta0": 0.5}, tolerance=tolerance)
    copy = fresh.slave.deserializeFMUState(serialized)
    fresh.slave.setFMUState(copy)
    assert steps(fresh, 0.2, 0.7) == second
    fresh.slave.freeFMUState(copy)
    fmu.slave.freeFMUState(state)


def test_a_state_keeps_the_pending_event(open_fmu3) -> None:
    """A state taken at an early return still has the bounce to apply when it is restored, even
    in a fresh instance from its serialized bytes."""
    fmu = open_fmu3("bouncing_ball_cvode", tolerance=1e-10, event_mode=True)
    t = 0.0
    while not (result := fmu.slave.doStep(t, 0.01))[0]:
        t = result[3]
    state = fmu.slave.serializeFMUState(fmu.slave.getFMUState())
    v_before = fmu.get("v")
    fresh = open_fmu3("bouncing_ball_cvode", tolerance=1e-10, event_mode=True)
    fresh.slave.setFMUState(fresh.slave.deserializeFMUState(state))
    assert "is not handled yet" in fresh.refused(fresh.slave.doStep, result[3], 0.01)
    fresh.slave.enterEventMode()
    assert fresh.slave.updateDiscreteStates()[3] is True
    assert fresh.get("v") == -E * v_before


# ------------------------------------------------------------------------------ state machine
def test_calls_in_the_wrong_state_are_refused_with_a_message(open_fmu3) -> None:
    fmu = open_fmu3("pendulum_cvode", initialize=False)
    assert fmu.refused(fmu.slave.doStep, 0.0, 0.1) == "fmi3DoStep is not allowed in Instantiated"
    assert fmu.refused(fmu.slave.getFloat64, [fmu.vr("theta")]) == \
        "fmi3GetFloat64 is not allowed in Instantiated"
    assert fmu.refused(fmu.slave.exitInitializationMode) == \
        "fmi3ExitInitializationMode is not allowed in Instantiated"
    fmu.slave.enterInitializationMode(startTime=0.0)
    assert fmu.refused(fmu.slave.enterStepMode) == \
        "fmi3EnterStepMode is not allowed in Initialization Mode"
    fmu.slave.exitInitializationMode()
    assert fmu.refused(fmu.slave.enterEventMode) == \
        "fmi3EnterEventMode: the instance was created with eventModeUsed = false"
    assert fmu.refused(fmu.slave.updateDiscreteStates) == \
        "fmi3UpdateDiscreteStates is not allowed in Step Mode"
    assert fmu.refused(fmu.set, "m", 50.0).startswith(
        "fmi3SetFloat64: m is a fixed parameter and cannot be changed in step mode (set it "
        "before fmi3ExitInitializationMode, or use fmi3Reset)")
    fmu.slave.terminate()
    assert fmu.refused(fmu.slave.doStep, 0.0, 0.1) == "fmi3DoStep is not allowed in Terminated"


def test_event_mode_calls_follow_the_state_machine(open_fmu3) -> None:
    fmu = open_fmu3("bouncing_ball_euler", event_mode=True, initialize=False)
    fmu.slave.enterInitializationMode(startTime=0.0)
    fmu.slave.exitInitializationMode()  # into Event Mode: eventModeUsed
    assert fmu.refused(fmu.slave.doStep, 0.0, 0.1) == "fmi3DoStep is not allowed in Event Mode"
    fmu.slave.enterStepMode()
    t = 0.0
    while not (result := fmu.slave.doStep(t, 0.01))[0]:
        t = result[3]
    assert fmu.refused(fmu.slave.doStep, result[3], 0.01).startswith(
        "fmi3DoStep: the internal event at t = ")
    fmu.slave.enterEventMode()
    assert fmu.refused(fmu.slave.enterStepMode).endswith(
        "is not applied yet (call fmi3UpdateDiscreteStates first)")


def test_event_mode_needs_internal_events(tmp_path) -> None:
    path = fmu_path("pendulum_cvode_fmi3")
    description = read_model_description(path)
    slave = FMU3Slave(guid=description.guid, unzipDirectory=extract(path, unzipdir=tmp_path),
                      modelIdentifier=description.coSimulation.modelIdentifier,
                      instanceName="P")
    messages: list[str] = []
    with pytest.raises(Exception, match="Failed to instantiate FMU"):
        slave.instantiate(eventModeUsed=True,
                          logMessage=lambda env, status, category, message:
                          messages.append(message.decode()))
    assert messages == ["fmi3InstantiateCoSimulation: eventModeUsed is true but this FMU has no "
                        "event mode (hasEventMode=\"false\": the model has no internal events "
                        "and no clocks)"]


@pytest.mark.parametrize(("failure", "status", "kind"), [
    (0, 3, "failure"),  # fmi3Error
    (1, 4, "fatal failure"),  # fmi3Fatal
    (2, 2, "discard"),  # fmi3Discard
])
def test_step_refusals_map_onto_fmi3_statuses(open_fmu3, failure: int, status: int,
                                              kind: str) -> None:
    fmu = open_fmu3("failing", starts={"fail_time": 0.5, "failure": failure})
    fmu.slave.doStep(0.0, 0.5)
    with pytest.raises(fmpy.fmi1.FMICallException) as caught:
        fmu.slave.doStep(0.5, 0.1)
    assert caught.value.status == status
    assert fmu.messages[-1][1] == "fmi3DoStep from t = 0.5 to 0.59999999999999998: the " \
        f"simulation passed fail_time (a deliberate {kind})"


@pytest.mark.parametrize("early_return_allowed", [True, False])
def test_termination_ends_the_step_at_the_stop_time(tmp_path,
                                                    early_return_allowed: bool) -> None:
    path = fmu_path("terminating_fmi3")
    description = read_model_description(path)
    slave = FMU3Slave(guid=description.guid, unzipDirectory=extract(path, unzipdir=tmp_path),
                      modelIdentifier=description.coSimulation.modelIdentifier,
                      instanceName="T")
    slave.instantiate(earlyReturnAllowed=early_return_allowed)
    slave.enterInitializationMode(startTime=0.0)
    slave.exitInitializationMode()
    assert slave.doStep(0.0, 0.75) == (False, False, False, 0.75)
    assert slave.doStep(0.75, 0.5) == (False, True, early_return_allowed, 1.0)
    assert slave.getFloat64([0]) == [1.0]  # y = t, stopped at stop_time = 1
    slave.terminate()
    slave.freeInstance()


def test_directional_derivatives_are_those_of_the_fmi2_build(open_fmu3, open_fmu) -> None:
    fmi3 = open_fmu3("pendulum_cvode", starts={"theta0": 0.5})
    fmi2 = open_fmu("pendulum_cvode", starts={"theta0": 0.5})
    steps(fmi3, 0.0, 0.3)
    for k in range(30):
        fmi2.slave.doStep(k * 0.01, 0.01)
    unknown, known = [fmi3.vr("alpha")], [fmi3.vr("torque")]
    assert fmi3.slave.getDirectionalDerivative(unknown, known, [1.0]) == \
        fmi2.slave.getDirectionalDerivative(unknown, known, [1.0])
    assert fmi3.slave.getDirectionalDerivative(unknown, known, [1.0])[0] == 1.0 / 20.0


# ------------------------------------------------------------------------------ Model Exchange
@pytest.mark.parametrize("stem", BUILT)
def test_model_exchange_is_declared_beside_co_simulation(stem: str) -> None:
    description = read_model_description(fmu_path(stem + "_fmi3"))
    me, cs = description.modelExchange, description.coSimulation
    assert me.modelIdentifier == cs.modelIdentifier == stem + "_fmi3"
    assert me.canGetAndSetFMUstate and me.canSerializeFMUstate  # FMPy keeps FMI 2.0 spelling
    assert not me.needsCompletedIntegratorStep
    assert description.numberOfContinuousStates == \
        read_model_description(fmu_path(stem)).numberOfContinuousStates


@pytest.mark.parametrize("stem", [s for s in BUILT if s != "failing"])
def test_fmpy_integrates_the_model_exchange_build_as_the_fmi2_one(stem: str) -> None:
    """The same model code behind both versions' Model Exchange calls: FMPy's CVODE takes the
    same steps and finds the same events, to the last bit."""
    fmi2, fmi3 = (fmpy.simulate_fmu(fmu_path(name), fmi_type="ModelExchange", solver="CVode",
                                    relative_tolerance=1e-8)
                  for name in (stem, stem + "_fmi3"))
    assert fmi3.dtype.names == fmi2.dtype.names
    for name in fmi2.dtype.names:
        np.testing.assert_array_equal(fmi3[name], fmi2[name], err_msg=name)


def test_bouncing_ball_as_model_exchange_through_syssimx_bounces_at_the_closed_form() -> None:
    """syssimx's CVODE finds each bounce with the FMU's event indicator, inside its step, and
    handles it with fmi3EnterEventMode and fmi3UpdateDiscreteStates: no rollback."""
    from syssimx import FMUComponent, System
    from test_fmu_bouncing_ball import closed_form_bounces

    ball = FMUComponent("B", fmu_path("bouncing_ball_cvode_fmi3"), interface="model-exchange",
                        tolerance=1e-12)
    system = System("ball")
    system.add_component(ball)
    system.initialize(0.0)
    result = system.run(0.0, 3.0, 0.01)
    np.testing.assert_allclose([e.t for e in result.events], closed_form_bounces(6), rtol=0,
                               atol=1e-8)
    assert {(e.event, e.own) for e in result.events} == {("state_event", True)}
    assert (result.statistics.own_events, result.statistics.state_restores) == (6, 0)
