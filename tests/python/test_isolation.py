"""Isolated FMUs: the binary runs in a host process, so a crash, an abort, an exit or a hang in
the FMU becomes a SimulationError, and everything else gives the in-process numbers bit for bit.

The misbehaving FMU (tests/c/hostile) is built by meson beside the tests, not installed: it is
found in SYSSIMX_BUILD_DIR or in the build directory scripts/install.sh keeps (build/release).
"""

from __future__ import annotations

import functools
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from syssimx import ConfigurationError, FMUComponent, SimulationError, System, fmus
from syssimx._paths import build_dir

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
FMI2_FATAL = 4


def hostile_fmu() -> str:
    build = build_dir() or ROOT / "build" / "release"
    path = build / "tests" / "c" / "hostile" / "hostile.fmu"
    if not path.is_file():
        pytest.skip(f"the hostile test FMU is not built ({path} is missing): run meson compile")
    return str(path)


def child_processes() -> set[int]:
    """This process's children, zombies included, read from /proc."""
    found = set()
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            text = stat.read_text()
        except OSError:  # the process ended meanwhile
            continue
        parent = text.rsplit(")", 1)[1].split()[1]
        if int(parent) == os.getpid():
            found.add(int(stat.parent.name))
    return found


def hostile_system(mode: int, step_timeout: float | None = None) -> tuple[System, FMUComponent]:
    hostile = FMUComponent("H", hostile_fmu(), isolated=True, step_timeout=step_timeout)
    hostile.set_parameters(mode=mode, fail_time=0.45)
    system = System("hostile")
    system.add_component(hostile)
    system.initialize(0.0)
    return system, hostile


def run_pendulum(fmu: str, isolated: bool) -> tuple[np.ndarray, dict[str, np.ndarray], dict]:
    pendulum = FMUComponent("P", fmus.path(fmu), isolated=isolated)
    pendulum.set_parameters(theta0=0.5, omega0=0.2)
    system = System("one pendulum")
    system.add_component(pendulum)
    system.initialize(0.0)
    t, data = system.run(0.0, 2.0, 0.01)["P"]
    return t.copy(), {k: v.copy() for k, v in data.items()}, pendulum.instance.counters()


@pytest.mark.parametrize("fmu", ["pendulum_euler", "pendulum_cvode", "pendulum_cvode_fmi1"])
def test_isolated_fmu_gives_the_in_process_results_bit_for_bit(fmu: str) -> None:
    t_here, here, calls_here = run_pendulum(fmu, isolated=False)
    t_there, there, calls_there = run_pendulum(fmu, isolated=True)
    assert np.array_equal(t_here, t_there)
    assert here.keys() == there.keys() == {"theta", "omega", "alpha"}
    for name in here:
        assert np.array_equal(here[name], there[name]), name
    assert calls_here == calls_there
    assert calls_there["do_step"] == 200


def reference_fmu(name: str) -> str:
    root = Path(os.environ.get("SYSSIMX_REFERENCE_FMUS", ROOT.parent / "shared" / "reference-fmus"))
    path = root / "fmi2" / f"{name}.fmu"
    if not path.is_file():
        pytest.skip(f"the Reference FMUs are not available ({path} is missing)")
    return str(path)


@pytest.mark.parametrize(("name", "inputs"), [
    ("Feedthrough", {"Float64_continuous_input": 1.5, "Int32_input": 7, "Boolean_input": True,
                     "Enumeration_input": 2}),
    ("Stair", {}),
    ("BouncingBall", {}),
])
def test_reference_fmus_isolated_give_the_in_process_outputs(name: str,
                                                             inputs: dict[str, object]) -> None:
    """Third-party binaries through the host, Integer and Boolean values included."""
    runs = []
    for isolated in (False, True):
        fmu = FMUComponent("R", reference_fmu(name), isolated=isolated)
        fmu.set_inputs(inputs)
        system = System("reference")
        system.add_component(fmu)
        system.initialize(0.0)
        _, data = system.run(0.0, 3.0, 0.01)["R"]
        runs.append({k: v.copy() for k, v in data.items()})
        fmu.free()
    # the host forwards no String calls: isolated, String outputs are no ports
    assert {k for k, v in runs[0].items() if v.dtype != object} == runs[1].keys()
    for port in runs[1]:
        assert np.array_equal(runs[0][port], runs[1][port]), port
    if name == "Feedthrough":
        assert runs[1]["Int32_output"][-1] == 7 and runs[1]["Boolean_output"][-1] == 1


@pytest.mark.parametrize("solver", ["cvode", "euler"])
def test_seed_scenario_isolated_locates_the_in_process_event_times(
    solver: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """examples/pendulum_wall.py as written, its FMUComponent isolated: rollback with
    fmi2Get/SetFMUstate through the host, the handler's reinitialize (an fmi2Reset), same
    events to the bit."""
    monkeypatch.syspath_prepend(str(EXAMPLES))
    import pendulum_wall

    runs = []
    for isolated in (False, True):
        monkeypatch.setattr(pendulum_wall, "FMUComponent",
                            functools.partial(FMUComponent, isolated=isolated))
        system, pendulum = pendulum_wall.build(solver)
        result = system.run(0.0, 3.0, 0.05)
        runs.append(([e.t for e in result.events], result["P"][1]["theta"].copy(),
                     pendulum.instance.counters()))
        pendulum.free()  # a System with a Python handler may outlive the test
    (events_here, theta_here, calls_here), (events_there, theta_there, calls_there) = runs
    assert len(events_there) == 3
    assert events_there == events_here
    assert abs(events_there[0] - pendulum_wall.QUARTER_PERIOD) < (1e-9 if solver == "cvode"
                                                                   else 3e-6)
    assert np.array_equal(theta_here, theta_there)
    assert calls_there == calls_here
    # one instance; the handler's reinitialize resets it at each of the three events
    assert calls_there["set_state"] > 0
    assert (calls_there["instantiate"], calls_there["reset"]) == (1, 3)


def test_fmu_state_serializes_through_the_host_to_the_in_process_bytes() -> None:
    blobs = []
    for isolated in (False, True):
        pendulum = FMUComponent("P", fmus.path("pendulum_euler"), isolated=isolated)
        pendulum.set_parameters(theta0=0.5)
        pendulum.initialize(0.0)
        instance = pendulum.instance
        state = instance.getFMUstate()
        instance.doStep(0.0, 0.1)
        after_step = instance.getReal([pendulum.value_reference("theta")])
        instance.setFMUstate(state)
        instance.doStep(0.0, 0.1)
        assert instance.getReal([pendulum.value_reference("theta")]) == after_step
        blob = instance.serializeFMUstate(state)
        copy = instance.deserializeFMUstate(blob)
        assert instance.serializeFMUstate(copy) == blob
        blobs.append(blob)
        pendulum.free()
    assert blobs[0] == blobs[1]


@pytest.mark.parametrize(("mode", "how"), [
    (1, "died of signal 11 (SIGSEGV"),
    (2, "died of signal 6 (SIGABRT"),
    (3, "exited with status 3"),
])
def test_crash_becomes_a_simulation_error_naming_component_time_and_signal(
    mode: int, how: str
) -> None:
    before = child_processes()  # hosts of other tests' components may still run
    system, hostile = hostile_system(mode)
    with pytest.raises(SimulationError) as info:
        system.run(0.0, 1.0, 0.1)
    error = info.value
    assert error.component == "H"
    assert error.time == pytest.approx(0.4)  # the step from 0.4 to 0.5 passes fail_time
    assert error.status == FMI2_FATAL
    assert error.fmu_message.startswith(f"the FMU process {how}")
    assert error.fmu_message.endswith("in fmi2DoStep")
    assert "'H'" in str(error) and "t=0.4" in str(error) and how in str(error)
    t, data = system.get_history()["H"]
    np.testing.assert_allclose(t, [0.0, 0.1, 0.2, 0.3, 0.4], atol=1e-12)
    np.testing.assert_array_equal(data["y"], t)
    assert child_processes() <= before  # reaped: no zombie
    unzip_dir = hostile._unzip_dir
    hostile.free()
    assert not unzip_dir.exists()


def test_step_timeout_kills_a_hung_fmu_and_leaves_nothing_behind() -> None:
    before = child_processes()
    system, hostile = hostile_system(mode=4, step_timeout=0.3)
    with pytest.raises(SimulationError) as info:
        system.run(0.0, 1.0, 0.1)
    assert info.value.component == "H"
    assert info.value.time == pytest.approx(0.4)
    assert info.value.fmu_message == ("fmi2DoStep did not return within the step timeout of "
                                      "0.3 s: the FMU process was killed")
    assert child_processes() <= before
    unzip_dir = hostile._unzip_dir
    hostile.free()
    assert not unzip_dir.exists()


def test_step_timeout_names_the_fmi1_call_of_a_hung_fmi1_fmu() -> None:
    """tests/fmus/fmi1_stuck never returns from fmiDoStep at t = 0.5."""
    path = (build_dir() or ROOT / "build" / "release") / "tests" / "fmus" / "fmi1_stuck" / \
        "fmi1_stuck.fmu"
    if not path.is_file():
        pytest.skip(f"the stuck FMI 1.0 test FMU is not built ({path} is missing)")
    before = child_processes()
    stuck = FMUComponent("F", str(path), isolated=True, step_timeout=0.3)
    system = System("stuck")
    system.add_component(stuck)
    system.initialize(0.0)
    with pytest.raises(SimulationError) as info:
        system.run(0.0, 1.0, 0.1)
    assert info.value.time == pytest.approx(0.5)
    assert info.value.fmu_message == ("fmiDoStep did not return within the step timeout of "
                                      "0.3 s: the FMU process was killed")
    stuck.free()
    assert child_processes() <= before


def test_after_a_crash_the_next_initialize_starts_a_new_host() -> None:
    before = child_processes()
    system, hostile = hostile_system(mode=1)
    with pytest.raises(SimulationError, match="SIGSEGV"):
        system.run(0.0, 1.0, 0.1)
    hostile.set_parameters(mode=0)
    system.initialize(0.0)
    _, data = system.run(0.0, 1.0, 0.1)["H"]
    np.testing.assert_allclose(data["y"], np.linspace(0.0, 1.0, 11), atol=1e-12)
    assert len(child_processes() - before) == 1
    hostile.free()
    assert child_processes() <= before


def test_calls_after_the_host_died_are_refused_naming_the_fatal_call() -> None:
    """FMI 2.0 allows no call after fmi2Fatal: the binding refuses it without asking a host."""
    system, hostile = hostile_system(mode=3)
    with pytest.raises(SimulationError, match=r"the FMU process exited with status 3 in "
                                              r"fmi2DoStep"):
        system.run(0.0, 1.0, 0.1)
    with pytest.raises(Exception, match=r"fmi2GetReal refused: fmi2DoStep returned fmi2Fatal "
                                        r"earlier"):
        hostile.instance.getReal([0])


def test_a_component_made_in_a_thread_that_ended_still_runs() -> None:
    """The host lives as long as the engine's process, not as long as the thread that
    started it."""
    made: list[tuple[System, FMUComponent]] = []
    worker = threading.Thread(target=lambda: made.append(hostile_system(mode=0)))
    worker.start()
    worker.join()
    system, hostile = made[0]
    _, data = system.run(0.0, 1.0, 0.1)["H"]
    np.testing.assert_allclose(data["y"], np.linspace(0.0, 1.0, 11), atol=1e-12)
    hostile.free()


ORPHAN_SCRIPT = """
import sys
sys.path.insert(0, {tests!r})
from test_isolation import child_processes, hostile_system
system, hostile = hostile_system(mode=4)
print(*child_processes(), flush=True)
system.run(0.0, 1.0, 0.1)  # never returns: no step_timeout
"""


def test_a_host_stuck_in_the_fmu_ends_when_the_engine_process_is_killed() -> None:
    script = ORPHAN_SCRIPT.format(tests=str(Path(__file__).parent))
    with subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                          text=True) as engine:
        assert engine.stdout is not None
        line = engine.stdout.readline()
        hosts = [int(pid) for pid in line.split()]
        assert len(hosts) == 1, line
        engine.send_signal(signal.SIGKILL)
        engine.wait()
    host_stat = Path(f"/proc/{hosts[0]}/stat")
    for _ in range(500):  # the host notices within milliseconds; give it 5 s on a busy machine
        if not host_stat.exists() or host_stat.read_text().rsplit(")", 1)[1].split()[0] == "Z":
            break
        time.sleep(0.01)
    else:
        os.kill(hosts[0], signal.SIGKILL)
        pytest.fail("the orphaned FMU host kept running after its engine process was killed")


@pytest.mark.parametrize("isolated", [False, True])
def test_logger_format_without_arguments_is_logged_as_raw_text(isolated: bool) -> None:
    """An FMU logging "%s%s%n" with no arguments: the "%n" conversion is refused and the raw
    text is the message, in process too."""
    hostile = FMUComponent("H", hostile_fmu(), isolated=isolated)
    hostile.set_parameters(mode=5, fail_time=0.45)
    system = System("hostile")
    system.add_component(hostile)
    system.initialize(0.0)
    with pytest.raises(SimulationError) as info:
        system.run(0.0, 1.0, 0.1)
    assert info.value.fmu_message == "%s%s%n"
    assert info.value.time == pytest.approx(0.4)
    assert info.value.status == 3  # fmi2Error, as the FMU returned


def test_step_timeout_needs_isolation_and_a_positive_number() -> None:
    with pytest.raises(ConfigurationError, match=r"'P': step_timeout needs isolated=True"):
        FMUComponent("P", fmus.path("pendulum_euler"), step_timeout=1.0)
    with pytest.raises(ConfigurationError,
                       match=r"'P': step_timeout must be a positive number of seconds, got 0"):
        FMUComponent("P", fmus.path("pendulum_euler"), isolated=True, step_timeout=0)
