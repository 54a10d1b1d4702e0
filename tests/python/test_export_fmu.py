"""System.export_fmu and `syssimx export`: the seed's pendulum against a wall as one
Co-Simulation FMU (FMI 2.0 and 3.0) whose binary is the engine, run by FMPy alone (no syssimx
importable, a copy in a fresh folder), validated by FMPy, and imported by syssimx itself, which
rolls it back to locate an event on its outputs. What cannot go into the binary is refused."""

from __future__ import annotations

import shutil
import subprocess
import zipfile
from pathlib import Path

import numpy as np
import pytest
from exported_fmus import STEP, STOP_TIME, export_seed, run_with_fmpy_alone, seed_system
from fixture_fmus import fmu_path
from fmpy import simulate_fmu
from fmpy.validation import validate_fmu
from osp_files import write_osp
from syssimx import (
    CoSimComponent,
    EventConnection,
    FMUComponent,
    HybridAlgorithm,
    System,
    _paths,
    fmus,
)
from syssimx.cli.main import main
from syssimx.errors import ConfigurationError
from syssimx.osp import read as read_osp
from syssimx.system_files import read_system_file

QUARTER_PERIOD = 0.46507759431173046  # the seed's first wall hit (DESIGN.md)
TOL_TIME = 1e-9  # the description's tol_time
# libcosim (libcosimpy 0.0.6, its fixedStep algorithm at 0.05 s, 20 steps) running the FMI 2.0
# export as the one simulator of an OSP system structure, measured once with
# benchmarks/exported_fmu_peers.py: P.theta, P.omega and last_event_time after the steps that
# end at 0.5 s and at 1 s. libcosim's communication points are whole nanoseconds (0.15, where
# FMPy's are 0.15000000000000002), so the inner steps end at other doubles: CVODE's solution
# (rtol 1e-10) differs by up to 5.4e-9 from syssimx's own run, the wall hit by 2e-13 s.
LIBCOSIM = {0.5: (0.059146143026729284, 1.6855345129332961, 0.46507759392864845),
            1.0: (0.4862917423803598, -0.39087992360397367, 0.46507759392864845)}


@pytest.fixture(scope="module")
def exported(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    folder = tmp_path_factory.mktemp("exported")
    return {version: export_seed(folder, version) for version in ("2.0", "3.0")}


@pytest.fixture(scope="module")
def own_run() -> tuple[np.ndarray, dict[str, np.ndarray], float]:
    """syssimx's own run of the description: the grid samples (the event instants' samples
    left out) and the first event's time."""
    system = seed_system()
    system.initialize(0.0)
    result = system.run(0.0, STOP_TIME, STEP)
    times, values = system.components["P"].get_history_arrays(["theta", "omega"])
    on_grid = np.isclose(times / STEP, np.round(times / STEP), rtol=0, atol=1e-9)
    # an event instant's two samples: the grid keeps the last sample at each grid time
    keep = on_grid & np.append(times[1:] != times[:-1], True)
    return times[keep], {f"P.{n}": v[keep] for n, v in values.items()}, result.events[0].t


@pytest.mark.parametrize("fmi_version", ["2.0", "3.0"])
def test_fmpy_alone_runs_the_export_as_syssimx_runs_the_system(exported, own_run, fmi_version):
    """Outputs equal at every grid point, the wall hit inside at syssimx's event time."""
    times, values, event_time = own_run
    result = run_with_fmpy_alone(exported[fmi_version])
    np.testing.assert_array_equal(result["time"], times)
    for name, expected in values.items():
        np.testing.assert_array_equal(result[name], expected, err_msg=name)
    assert abs(event_time - QUARTER_PERIOD) < TOL_TIME
    hit = int(np.searchsorted(result["time"], event_time))  # the first grid point after it
    assert result["events"][hit - 1] == 0 and result["events"][hit] == 1
    assert abs(result["last_event_time"][hit] - event_time) <= TOL_TIME
    # theta stays on its side of the wall: the omega jump happened inside the step
    assert result["P.omega"][hit - 1] < 0 < result["P.omega"][hit]


@pytest.mark.parametrize("fmi_version", ["2.0", "3.0"])
def test_fmpy_validates_the_export(exported, fmi_version):
    assert validate_fmu(str(exported[fmi_version])) == []


@pytest.mark.parametrize("fmi_version", ["2.0", "3.0"])
def test_the_archive_holds_binary_plan_map_and_members(exported, fmi_version):
    platform = "linux64" if fmi_version == "2.0" else "x86_64-linux"
    with zipfile.ZipFile(exported[fmi_version]) as archive:
        names = set(archive.namelist())
        description = archive.read("modelDescription.xml").decode()
    identifier = exported[fmi_version].stem
    assert {f"binaries/{platform}/{identifier}.so", "resources/system.plan",
            "resources/export.map", "resources/members/pendulum_cvode/modelDescription.xml",
            "resources/members/pendulum_cvode/binaries/linux64/pendulum_cvode.so"} <= names
    state = "FMUState" if fmi_version == "3.0" else "FMUstate"
    assert f'canGetAndSet{state}="true"' in description
    assert f'canSerialize{state}="true"' in description
    if fmi_version == "3.0":  # it returns early at its own events, and has event mode
        assert 'mightReturnEarlyFromDoStep="true"' in description
        assert 'hasEventMode="true"' in description
    assert 'unit="rad"' in description


def test_the_binary_needs_libc_and_libm_only_and_exports_fmi_functions():
    binary = _paths.export_binary()
    readelf = shutil.which("readelf")
    assert readelf is not None, "binutils' readelf is needed to read the binary's dependencies"
    dynamic = subprocess.run([readelf, "-d", str(binary)], check=True, capture_output=True,
                             text=True).stdout
    needed = {line.split("[")[1].rstrip("]") for line in dynamic.splitlines()
              if "(NEEDED)" in line}
    assert needed <= {"libc.so.6", "libm.so.6"}, needed
    symbols = subprocess.run([readelf, "--dyn-syms", "-W", str(binary)], check=True,
                             capture_output=True, text=True).stdout
    defined = {line.split()[7] for line in symbols.splitlines()
               if len(line.split()) >= 8 and line.split()[6] != "UND"
               and line.split()[3] == "FUNC"}
    assert defined and all(name.startswith(("fmi2", "fmi3")) for name in defined), defined
    assert {"fmi2DoStep", "fmi2GetFMUstate", "fmi3DoStep", "fmi3EnterEventMode"} <= defined


def test_syssimx_imports_its_export_and_locates_an_outer_event_by_rolling_it_back(exported,
                                                                               own_run):
    """The outer hybrid algorithm watches the export's output P.omega fall through zero: after
    the elastic bounce inside, the pendulum climbs back to theta0, where omega is zero at twice
    the wall hit's time (the motion after the bounce mirrors the motion before it). Locating it
    rolls the FMU back (fmi2GetFMUstate/SetFMUstate of the whole inner system)."""
    outer = System("outer")
    wall = FMUComponent("W", exported["2.0"])
    assert wall.can_get_set_state
    wall.add_event_indicator("at_top", variable="P.omega", direction=-1)
    wall.add_event_handler("seen", lambda component, events, t: None)
    outer.add_component(wall)
    outer.add_event_connection(EventConnection("W", "at_top", "W", "seen"))
    outer.set_algorithm(HybridAlgorithm(tol_time=TOL_TIME))
    outer.initialize(0.0)
    result = outer.run(0.0, STOP_TIME, 0.25)
    # omega starts at zero and falls: an event at the start, then the one at the top
    times = [e.t for e in result.events]
    assert times[0] == 0.0 and len(times) == 2
    assert abs(times[1] - 2 * own_run[2]) < 2 * TOL_TIME
    assert result.statistics.state_restores > 0
    assert wall.instance.counters()["set_state"] > 0  # the export's fmi2SetFMUstate


def test_libcosim_ran_the_fmi2_export_in_an_osp_file_as_syssimx_runs_the_system(own_run):
    times, values, event_time = own_run
    for t, (theta, omega, last_event_time) in LIBCOSIM.items():
        k = int(np.argmin(np.abs(times - t)))
        assert abs(theta - values["P.theta"][k]) < 1e-8
        assert abs(omega - values["P.omega"][k]) < 1e-8
        assert abs(last_event_time - event_time) < TOL_TIME


def test_fmi3_importer_allowing_early_return_gets_the_step_back_at_the_wall_hit(exported):
    """syssimx instantiates an FMI 3.0 FMU that can return early with earlyReturnAllowed: the
    export's doStep returns right after the wall hit inside (one doStep more than the grid's
    20), and the run goes on on the grid."""
    outer = System("outer")
    wall = FMUComponent("W", exported["3.0"])
    outer.add_component(wall)
    outer.initialize(0.0)
    outer.run(0.0, STOP_TIME, STEP)
    assert wall.instance.counters()["do_step"] == round(STOP_TIME / STEP) + 1
    times, values = wall.get_history_arrays(["P.omega", "events"])
    assert len(times) == round(STOP_TIME / STEP) + 1  # the grid only
    assert values["events"][-1] == 1


def bounce_times(stop: float) -> list[float]:
    """bouncing_ball's bounces before `stop` in closed form: dropped from 1 m at rest under
    g = 9.81, each rebound keeping 0.8 of the impact speed."""
    gravity, times = 9.81, []
    t, speed = np.sqrt(2 / gravity), np.sqrt(2 * gravity)
    while t < stop:
        times.append(float(t))
        speed *= 0.8
        t += 2 * speed / gravity
    return times


def test_an_fmi3_export_returns_early_at_a_model_exchange_member_s_own_bounces(tmp_path):
    """Our bouncing ball as a Model Exchange member (its bounces are its own state events, no
    indicator's) inside an FMI 3.0 export: FMPy allowing early return (0.1 s steps) gets each
    doStep back right after a bounce, at its closed-form time within 1e-8, the ball on the
    floor going up; not allowing it, FMPy's samples are the grid's only."""
    system = System("ball")
    ball = FMUComponent("B", fmus.path("bouncing_ball_cvode"), interface="model-exchange",
                        tolerance=1e-12)
    ball.set_parameters(e=0.8, gap_tol=1e-6)
    system.add_component(ball)
    fmu = system.export_fmu(tmp_path / "ball.fmu", fmi_version="3.0", outputs=["B.h", "B.v"],
                            step_size=0.1)
    early = simulate_fmu(str(fmu), stop_time=3.0, output_interval=0.1,
                         early_return_allowed=True, output=["B.h", "B.v"])
    times = early["time"]
    off_grid = np.abs(times / 0.1 - np.round(times / 0.1)) > 1e-6
    bounces = bounce_times(3.0)
    assert len(bounces) == 6
    np.testing.assert_allclose(times[off_grid], bounces, rtol=0, atol=1e-8)
    assert np.all(np.abs(early["B.h"][off_grid]) < 1e-6) and np.all(early["B.v"][off_grid] > 0)
    assert len(times) == 31 + len(bounces)
    plain = simulate_fmu(str(fmu), stop_time=3.0, output_interval=0.1, output=["B.h"])
    np.testing.assert_allclose(plain["time"], np.arange(31) * 0.1, rtol=0, atol=1e-12)


def swinging(theta0: float, torque: float) -> System:
    """The CVODE pendulum with no events, released at theta0 under a constant torque."""
    system = System("swing")
    pendulum = FMUComponent("P", fmus.path("pendulum_cvode"))
    pendulum.set_parameters(theta0=theta0, cvode_relative_tolerance=1e-10)
    pendulum.set_inputs({"torque": torque})
    system.add_component(pendulum)
    return system


def test_parameters_and_inputs_set_by_the_importer_are_the_members(tmp_path):
    """A pendulum with no events, its theta0 exported as a parameter and its torque as an
    input: FMPy's start value and constant input give syssimx's run with the same values, to
    the bit."""
    fmu = tmp_path / "swing.fmu"
    swinging(0.5, 0.0).export_fmu(fmu, outputs=["P.theta"], parameters=["P.theta0"],
                                  step_size=STEP)
    result = run_with_fmpy_alone(fmu, ["P.theta"], {"P.theta0": 0.25}, {"P.torque": 0.75})
    system = swinging(0.25, 0.75)
    system.initialize(0.0)
    system.run(0.0, STOP_TIME, STEP)
    times, values = system.components["P"].get_history_arrays(["theta"])
    np.testing.assert_array_equal(result["time"], times)
    np.testing.assert_array_equal(result["P.theta"], values["theta"])


def test_a_wrong_token_and_a_step_from_elsewhere_fail_with_the_reason_logged(exported,
                                                                          tmp_path, capsys):
    """Every failure reaches the importer's logger with its reason (FMPy's ctypes binding with
    its default callbacks, which print each message formatted)."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    description = read_model_description(exported["2.0"])
    unzipped = extract(exported["2.0"], unzipdir=tmp_path / "unzipped")

    def slave(guid: str) -> FMU2Slave:
        return FMU2Slave(guid=guid, unzipDirectory=unzipped, instanceName="wall",
                         modelIdentifier=description.coSimulation.modelIdentifier)
    with pytest.raises(Exception, match="Failed to instantiate"):
        slave("{not-this-token}").instantiate()
    assert "is not this FMU's" in capsys.readouterr().out
    wall = slave(description.guid)
    wall.instantiate()
    wall.setupExperiment(startTime=0.0)
    wall.enterInitializationMode()
    wall.exitInitializationMode()
    with pytest.raises(Exception, match="fmi2DoStep failed"):
        wall.doStep(0.3, STEP)
    assert "steps go on from where the last one ended" in capsys.readouterr().out
    wall.terminate()
    wall.freeInstance()


def test_a_serialized_state_restored_continues_from_the_importers_own_time(exported,
                                                                        tmp_path):
    """The state at 0.4 s (eight steps summed: 0.39999999999999997), serialized and
    deserialized, continues to 1 s past the wall hit exactly as the state kept in memory does;
    and from 0.4 as the importer writes it too (a communication point within 1e-9 steps of the
    system's time is that time). Each restored run differs from the run never restored by what
    the member's own restore does (pendulum_cvode restarts CVODE: 3e-10)."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    description = read_model_description(exported["2.0"])
    references = {v.name: v.valueReference for v in description.modelVariables}
    wall = FMU2Slave(guid=description.guid, instanceName="wall",
                     unzipDirectory=extract(exported["2.0"], unzipdir=tmp_path / "unzipped"),
                     modelIdentifier=description.coSimulation.modelIdentifier)
    wall.instantiate()
    wall.setupExperiment(startTime=0.0)
    wall.enterInitializationMode()
    wall.exitInitializationMode()

    def step_to_the_end(t: float) -> tuple[float, float, int]:
        while t < STOP_TIME - STEP / 2:
            wall.doStep(t, STEP)
            t += STEP
        theta, omega = wall.getReal([references["P.theta"], references["P.omega"]])
        return theta, omega, wall.getInteger([references["events"]])[0]
    t = 0.0
    for _ in range(8):
        wall.doStep(t, STEP)
        t += STEP
    assert t != 0.4
    kept = wall.getFMUstate()
    serialized = wall.serializeFMUstate(kept)
    never_restored = step_to_the_end(t)
    wall.setFMUstate(kept)
    restored = step_to_the_end(t)
    wall.setFMUstate(wall.deSerializeFMUstate(serialized))
    assert step_to_the_end(t) == restored
    wall.setFMUstate(wall.deSerializeFMUstate(serialized))
    from_0_4 = step_to_the_end(0.4)
    assert restored[2] == from_0_4[2] == never_restored[2] == 1
    np.testing.assert_allclose(restored[:2], never_restored[:2], rtol=0, atol=1e-8)
    np.testing.assert_allclose(from_0_4[:2], restored[:2], rtol=0, atol=1e-8)
    wall.terminate()
    wall.freeInstance()


def test_a_member_asking_to_stop_ends_the_importers_run_there(tmp_path):
    """The terminating fixture (a ramp that asks to stop at 0.3 s) inside the export: its
    request reaches the importer as the standard says (fmi2DoStep returns fmi2Discard,
    fmi2GetBooleanStatus(fmi2Terminated) is true), so FMPy and syssimx both end at 0.3 s."""
    system = System("ramp")
    ramp = FMUComponent("R", fmu_path("terminating"))
    ramp.set_parameters(stop_time=0.3)
    system.add_component(ramp)
    system.export_fmu(tmp_path / "ramp.fmu", step_size=STEP)
    result = run_with_fmpy_alone(tmp_path / "ramp.fmu", ["R.y"])
    assert result["time"][-1] == pytest.approx(0.3) and result["R.y"][-1] == pytest.approx(0.3)
    outer = System("outer")
    outer.add_component(FMUComponent("W", tmp_path / "ramp.fmu"))
    outer.initialize(0.0)
    run = outer.run(0.0, STOP_TIME, STEP)
    assert run.termination is not None and run.termination.component == "W"
    assert run.termination.time == pytest.approx(0.3)


def test_a_parameter_set_in_initialization_mode_initializes_the_members(tmp_path):
    """FMI lets an importer set a fixed parameter in initialization mode too: the members are
    initialized again with it, the run is that of a system built with it. After
    initialization mode it is refused."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    fmu = tmp_path / "swing.fmu"
    swinging(0.5, 0.0).export_fmu(fmu, outputs=["P.theta"], parameters=["P.theta0"],
                                  step_size=STEP)
    description = read_model_description(fmu)
    references = {v.name: v.valueReference for v in description.modelVariables}
    swing = FMU2Slave(guid=description.guid, instanceName="swing",
                      unzipDirectory=extract(fmu, unzipdir=tmp_path / "unzipped"),
                      modelIdentifier=description.coSimulation.modelIdentifier)
    swing.instantiate()
    swing.setupExperiment(startTime=0.0)
    swing.enterInitializationMode()
    swing.setReal([references["P.theta0"]], [0.25])
    assert swing.getReal([references["P.theta"]]) == [0.25]
    swing.exitInitializationMode()
    for k in range(round(STOP_TIME / STEP)):  # to the points of syssimx's grid, as FMPy does
        swing.doStep(k * STEP, (k + 1) * STEP - k * STEP)
    with pytest.raises(Exception, match="fmi2SetReal failed"):
        swing.setReal([references["P.theta0"]], [0.5])
    system = swinging(0.25, 0.0)
    system.initialize(0.0)
    system.run(0.0, STOP_TIME, STEP)
    assert swing.getReal([references["P.theta"]])[0] == \
        system.components["P"].get_history_arrays(["theta"])[1]["theta"][-1]
    swing.terminate()
    swing.freeInstance()


def test_the_command_line_exports_a_description(tmp_path, capsys):
    target = tmp_path / "wall.fmu"
    assert main(["export", str(Path(__file__).resolve().parents[2] / "examples"
                                / "pendulum_wall.yaml"), "-o", str(target),
                 "--fmi-version", "3.0", "--output", "P.theta"]) == 0
    assert "FMI 3.0" in capsys.readouterr().out
    with zipfile.ZipFile(target) as archive:
        description = archive.read("modelDescription.xml").decode()
    assert 'name="P.theta"' in description and 'name="P.torque"' in description
    assert 'name="P.omega"' not in description  # only the output asked for
    assert validate_fmu(str(target)) == []


@pytest.mark.parametrize("kind", ["osp", "ssp"])
def test_the_command_line_exports_a_system_file_of_three_fmus(tmp_path, kind):
    """libcosim's kind of system (tests/python/osp_files.py: two pendulums and a spring,
    variable groups, a LinearTransformation, step 0.01 s) exported from its OSP file, and from
    the SSP syssimx writes of it: FMPy's doStep of 0.05 s is five of the system's steps, the
    samples those of syssimx's own run of the file (its grid points and FMPy's communication
    points are other doubles: within 1e-14)."""
    structure = write_osp(tmp_path / "osp")
    system_file = structure if kind == "osp" else read_osp(structure).system.to_ssp(
        tmp_path / "coupled.ssp", start_time=0.0, stop_time=0.5, step_size=0.01)
    fmu = tmp_path / "coupled.fmu"
    assert main(["export", str(system_file), "-o", str(fmu)]) == 0
    imported = read_system_file(system_file)
    assert imported.experiment.step_size == 0.01
    stop = imported.experiment.stop_time
    system = imported.system
    system.initialize(0.0)
    system.run(0.0, stop, imported.experiment.step_size)
    times, values = system.components["P2"].get_history_arrays(["theta"])
    result = run_with_fmpy_alone(fmu, ["P2.theta"], stop_time=stop)
    at = [int(np.argmin(np.abs(times - t))) for t in result["time"]]
    np.testing.assert_allclose(times[at], result["time"], rtol=0, atol=1e-15)
    np.testing.assert_allclose(values["theta"][at], result["P2.theta"], rtol=0, atol=1e-14)


class Doubler(CoSimComponent):
    """A component written in Python."""


class SlowPendulum(FMUComponent):
    """An FMU component whose step runs Python (the seed's kind of subclass)."""

    def _do_step_internal(self, t: float, dt: float) -> None:
        super()._do_step_internal(t, dt)


class Printer:
    """An observer written in Python."""

    def step_complete(self, t: float, micro: int, values: object) -> None:
        print(t, micro, values)


def test_every_part_that_runs_python_is_named_in_one_refusal(tmp_path):
    system = seed_system()
    pendulum = system.components["P"]
    pendulum.add_event_indicator("low", func=lambda component: 1.0, direction=-1)
    pendulum.add_event_handler("on_low", lambda component, events, t: None)
    system.add_event_connection(EventConnection("P", "low", "P", "on_low"))
    system.add_component(Doubler("D"))
    system.add_component(SlowPendulum("S", fmus.path("pendulum_cvode")))
    system.add_observer(Printer())
    with pytest.raises(ConfigurationError) as refused:
        system.export_fmu(tmp_path / "never.fmu")
    message = str(refused.value)
    for part in ("Python component 'D'", "Python event indicator P.low",
                 "Python event handler of 'P'", "Python observer Printer",
                 "Python hooks of 'S' (SlowPendulum overrides do_step)"):
        assert part in message, (part, message)
    assert not (tmp_path / "never.fmu").exists()


def test_a_parameter_of_a_restarted_member_is_refused(tmp_path):
    """The restart handler starts P again from the values of the export: a parameter set in
    the FMU would hold until the first event only."""
    with pytest.raises(ConfigurationError, match=r"P\.L.*restarts"):
        seed_system().export_fmu(tmp_path / "never.fmu", parameters=["P.L"])


def test_an_isolated_member_is_refused(tmp_path):
    system = System("isolated")
    system.add_component(FMUComponent("P", fmus.path("pendulum_cvode"), isolated=True))
    with pytest.raises(ConfigurationError, match=r"isolated components \['P'\]"):
        system.export_fmu(tmp_path / "never.fmu")


def test_unknown_and_driven_ports_are_refused(tmp_path):
    system = seed_system()
    with pytest.raises(ConfigurationError, match="has no output 'nothing'"):
        system.export_fmu(tmp_path / "never.fmu", outputs=["P.nothing"])
    with pytest.raises(ConfigurationError, match="fmi_version"):
        system.export_fmu(tmp_path / "never.fmu", fmi_version="1.0")
