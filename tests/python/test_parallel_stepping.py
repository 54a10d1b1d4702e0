"""Stepping FMU components on several threads (`threads=N` of the coupling algorithms): the
same samples, statistics and errors as one thread, and what must stay on the calling thread
stays there."""

from __future__ import annotations

import os
import signal
import threading
import zipfile
from pathlib import Path

import coupled_pendulums  # two pendulum FMUs and the torsion spring FMU
import numpy as np
import pytest
from fixture_fmus import fmu_path
from syssimx import (
    CoSimComponent,
    EventConnection,
    FMUComponent,
    GaussSeidelAlgorithm,
    HybridAlgorithm,
    JacobiAlgorithm,
    System,
    fmus,
)
from syssimx.cli import main
from syssimx.core.port import PortSpec, PortType
from syssimx.errors import SimulationError
from syssimx.system.loader import build_system


def samples(system: System, tf: float = 2.0, dt: float = 0.01) -> tuple[dict, str]:
    result = system.run(0.0, tf, dt)
    arrays = {name: (result[name][0].copy(), {p: v.copy() for p, v in result[name][1].items()})
              for name in system.components}
    return arrays, str(result.statistics)


def assert_identical(a: dict, b: dict) -> None:
    assert a.keys() == b.keys()
    for name in a:
        assert np.array_equal(a[name][0], b[name][0])
        assert a[name][1].keys() == b[name][1].keys()
        for port in a[name][1]:
            assert np.array_equal(a[name][1][port], b[name][1][port]), f"{name}.{port}"


@pytest.mark.parametrize("algorithm", [JacobiAlgorithm, GaussSeidelAlgorithm])
def test_coupled_pendulums_identical_on_two_and_four_threads(algorithm: type) -> None:
    runs = {}
    for threads in (1, 2, 4):
        system = coupled_pendulums.build(algorithm(threads=threads))
        system.initialize(0.0)
        runs[threads] = samples(system)
    assert "doStep calls: 600" in runs[1][1]
    for threads in (2, 4):
        assert_identical(runs[1][0], runs[threads][0])
        assert runs[threads][1] == runs[1][1]


def reverse(pendulum: FMUComponent, _events: list[str], t: float) -> None:
    outputs = pendulum.get_outputs()
    pendulum.reinitialize(t, theta0=outputs["theta"].magnitude,
                          omega0=-outputs["omega"].magnitude)


def walled_pendulums(threads: int) -> System:
    """The coupled pendulums with a wall at theta = 0 for P1: events located by rolling back
    all three FMUs, every trial a coupled step on `threads` threads."""
    system = coupled_pendulums.build(JacobiAlgorithm(), rtol=1e-10)
    p1 = system.components["P1"]
    p1.add_event_indicator("wall", variable="theta", direction=-1)
    p1.add_event_handler("bounce", reverse)
    system.add_event_connection(EventConnection("P1", "wall", "P1", "bounce"))
    system.set_algorithm(HybridAlgorithm(coupling=JacobiAlgorithm(threads=threads)))
    system.initialize(0.0)
    return system


def test_hybrid_system_identical_on_two_threads() -> None:
    one, two = walled_pendulums(1), walled_pendulums(2)
    (samples_one, stats_one), (samples_two, stats_two) = samples(one), samples(two)
    assert len(one.history.get_all_event_histories()) > 0
    events_one = [(e.t, e.iterations) for e in one.run(2.0, 2.5, 0.01).events]
    events_two = [(e.t, e.iterations) for e in two.run(2.0, 2.5, 0.01).events]
    assert "localization iterations: 0" not in stats_one
    assert_identical(samples_one, samples_two)
    assert stats_two == stats_one
    assert events_two == events_one


def probe(name: str, partners: int) -> FMUComponent:
    """thread_probe: its output `thread` is the id of the thread that last stepped it; with
    partners = 2 it steps only while another such probe steps at the same time."""
    component = FMUComponent(name, fmu_path("thread_probe"))
    component.set_parameters(partners=partners)
    return component


def pendulums_and_failing(threads: int) -> System:
    """The calling thread takes R1, the first task, and waits in its step for a partner: the
    worker must take F, then R2. F fails on the worker in the step to 0.4. One thread steps
    the same system without the probes' wait."""
    system = System("failing")
    partners = 2 if threads > 1 else 0
    failing = FMUComponent("F", fmu_path("failing"))
    failing.set_parameters(fail_time=0.35)
    pendulum = FMUComponent("P3", fmus.path("pendulum_euler"))
    pendulum.set_parameters(theta0=0.3)
    for component in (probe("R1", partners), failing, probe("R2", partners), pendulum):
        system.add_component(component)
    system.set_algorithm(JacobiAlgorithm(threads=threads))
    system.initialize(0.0)
    return system


def test_failure_on_a_worker_names_component_and_time() -> None:
    messages = {}
    for threads in (1, 2):
        system = pendulums_and_failing(threads)
        with pytest.raises(SimulationError) as failure:
            system.run(0.0, 1.0, 0.1)
        messages[threads] = str(failure.value)
        t, _ = system.get_history()["P3"]
        assert list(t) == [0.0, 0.1, 0.2, 0.30000000000000004]  # stays readable
    assert "component 'F': fmi2DoStep failed at t=0.30000000000000004 with status fmi2Error" \
        in messages[1]
    assert messages[2] == messages[1]


class ThreadRecorder(CoSimComponent):
    """A Python component: notes the thread each of its steps runs on."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.output_specs["y"] = PortSpec("y", PortType.REAL, "out")
        self.threads: set[int] = set()

    def _do_step_internal(self, t: float, dt: float) -> None:
        self.threads.add(threading.get_ident())

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        self.outputs["y"].set(0.0, t)


def once_per_process_probe(tmp_path: Path) -> str:
    """thread_probe.fmu declaring canBeInstantiatedOnlyOncePerProcess."""
    target = tmp_path / "thread_probe_once.fmu"
    with zipfile.ZipFile(fmu_path("thread_probe")) as src, zipfile.ZipFile(target, "w") as dst:
        for item in src.infolist():
            data = src.read(item)
            if item.filename == "modelDescription.xml":
                data = data.replace(b"<CoSimulation ",
                                    b'<CoSimulation canBeInstantiatedOnlyOncePerProcess="true" ')
            dst.writestr(item, data)
    return str(target)


def test_python_components_and_once_per_process_fmus_stay_on_the_calling_thread(
        tmp_path: Path) -> None:
    # A and B step only together: the calling thread takes A (the first pool task), so the
    # worker steps B at the same time
    system = System("threads")
    system.add_component(probe("A", 2))
    system.add_component(probe("B", 2))
    system.add_component(FMUComponent("Once", once_per_process_probe(tmp_path)))
    recorder = ThreadRecorder("Python")
    system.add_component(recorder)
    system.set_algorithm(JacobiAlgorithm(threads=2))
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.1)
    caller = threading.get_native_id()
    thread = {name: set(result[name][1]["thread"][1:]) for name in ("A", "B", "Once")}
    assert thread["A"] == thread["Once"] == {caller}
    assert len(thread["B"]) == 1 and caller not in thread["B"]
    assert recorder.threads == {threading.get_ident()}


def test_threads_option_from_yaml_and_bad_values(tmp_path: Path) -> None:
    description = tmp_path / "system.yaml"
    description.write_text(
        "system: {name: two}\n"
        "components:\n"
        "  - {name: P1, fmu: pendulum_cvode}\n"
        "  - {name: P2, fmu: pendulum_cvode}\n"
        "algorithm: {type: gauss_seidel, threads: 2}\n")
    system = build_system(str(description))
    assert system.algorithm == GaussSeidelAlgorithm(threads=2)
    with pytest.raises(ValueError, match="Jacobi: threads must be between 1 and 256, not 0"):
        JacobiAlgorithm(threads=0).validate()
    with pytest.raises(ValueError, match=r"threads must be an integer, got 2\.0"):
        JacobiAlgorithm(threads=2.0).validate()  # type: ignore[arg-type]


def test_cli_run_threads_writes_the_same_csv(tmp_path: Path,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    description = str(Path(coupled_pendulums.__file__).with_suffix(".yaml"))
    one, two = tmp_path / "one.csv", tmp_path / "two.csv"
    assert main(["run", description, "--tf", "0.5", "-o", str(one)]) == 0
    assert main(["run", description, "--tf", "0.5", "--threads", "2", "-o", str(two)]) == 0
    assert two.read_bytes() == one.read_bytes()
    capsys.readouterr()
    assert main(["run", description, "--threads", "0"]) == 1
    assert capsys.readouterr().err == ("syssimx: error: Gauss-Seidel: threads must be between "
                                       "1 and 256, not 0\n")


def test_ctrl_c_stops_a_run_on_two_threads_and_it_goes_on() -> None:
    system = System("typo")
    for i in range(4):
        pendulum = FMUComponent(f"P{i}", fmus.path("pendulum_euler"))
        pendulum.set_parameters(theta0=0.1 * (i + 1))
        system.add_component(pendulum)
    system.set_algorithm(JacobiAlgorithm(threads=2))
    system.initialize(0.0)
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    # timeout only guards the test against running for hours if Ctrl-C were lost
    with pytest.raises(KeyboardInterrupt):
        system.run(0.0, 1.0, 1e-9, timeout=30.0)
    t, _ = system.get_history()["P3"]
    assert len(t) > 1000 and t[-1] == system.t
    result = system.run(system.t, system.t + 1e-8, 1e-9)
    assert len(result["P3"][0]) == len(t) + 10


def test_isolated_fmus_step_on_the_workers_with_the_same_results() -> None:
    # each isolated FMU has a host process and a socket of its own: nothing is shared
    runs = []
    for threads in (1, 2):
        system = System("isolated")
        for i in range(4):
            pendulum = FMUComponent(f"P{i}", fmus.path("pendulum_cvode"), isolated=i % 2 == 0)
            pendulum.set_parameters(theta0=0.1 * (i + 1))
            system.add_component(pendulum)
        system.set_algorithm(JacobiAlgorithm(threads=threads))
        system.initialize(0.0)
        runs.append(samples(system, tf=0.5))
    assert_identical(runs[0][0], runs[1][0])
    assert runs[1][1] == runs[0][1]


def bouncing_balls_as_model_exchange(threads: int) -> System:
    """Four balls the engine integrates (Model Exchange), dropped from different heights, their
    bounces their own events, and a master's indicator (an apex) on one of them located by
    rollback."""
    system = System("balls")
    for k in range(4):
        ball = FMUComponent(f"B{k}", fmus.path("bouncing_ball_cvode"),
                            interface="model-exchange", tolerance=1e-10)
        ball.set_parameters(h0=1.0 + 0.25 * k)
        system.add_component(ball)
    system.components["B0"].add_event_indicator("apex", variable="v", direction=-1)
    system.set_algorithm(HybridAlgorithm(coupling=JacobiAlgorithm(threads=threads)))
    system.initialize(0.0)
    return system


def test_model_exchange_components_identical_on_two_threads() -> None:
    runs = {}
    for threads in (1, 2):
        system = bouncing_balls_as_model_exchange(threads)
        result = system.run(0.0, 2.0, 0.01)
        runs[threads] = ({n: (result[n][0].copy(), {p: v.copy() for p, v in result[n][1].items()})
                          for n in system.components},
                         [(e.t, e.micro, e.component, e.event, e.own) for e in result.events],
                         str(result.statistics))
    assert_identical(runs[1][0], runs[2][0])
    assert runs[2][1:] == runs[1][1:]
    events = runs[1][1]
    assert {e[3] for e in events} == {"state_event", "apex"}
    assert sum(1 for e in events if e[3] == "state_event") >= 8
