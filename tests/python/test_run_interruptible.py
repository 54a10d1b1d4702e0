"""Every long loop of the engine stops within a second of the run's `timeout=` and on Ctrl-C,
not at the next grid point: a Model Exchange component's integrator steps, the step
control's retries and steps, the event localization's trials and an algebraic loop's
iterations, and the wait for an isolated FMU's host (here an FMI 1.0 FMU stuck in fmiDoStep,
which FMI 1.0 could not be isolated for before). Each system below runs one grid interval that
would take minutes (hours for some); before, the monitor was asked only at grid points, so
each ran on past its timeout until the interval was done. Each loop stops within a second of
the timeout, of SIGINT and of SIGTERM (before, SIGTERM killed the process: its stream lacked
the samples still in memory), and the file streamed holds exactly the samples recorded.

A step control's min_step below the time resolution (the spacing of times near 1 s) is refused
where the setting is read; where times are coarser than min_step, a step is at least two of
their roundings, so that time goes on (before, t + h == t: the run never ended)."""

from __future__ import annotations

import csv
import os
import signal
import subprocess
import sys
import threading
import time
import warnings
from pathlib import Path

import numpy as np
import pytest
from ecco_structure import Ecco, write_structure
from fixture_fmus import fmu_path
from syssimx import (
    Connection,
    CoSimComponent,
    EventConnection,
    FMUComponent,
    GaussSeidelAlgorithm,
    JacobiAlgorithm,
    PortSpec,
    PortType,
    StepControl,
    System,
    TableSource,
    fmus,
)
from syssimx._paths import build_dir
from syssimx.errors import ConfigurationError, RunInterrupted, SimulationTimeoutError
from syssimx.osp import read as read_osp
from syssimx.osp.errors import OSPError

# the unreachable tolerance's steps at min_step are warned of: expected here
pytestmark = pytest.mark.filterwarnings("ignore:.*still exceeded its tolerance")

TIMEOUT = 1.0
STOP_WITHIN = 1.0  # seconds past the timeout or the signal
SIGNAL_AFTER = 0.5  # seconds into the run
ROOT = Path(__file__).resolve().parents[2]


def integrator_bound() -> System:
    """An elastic ball (e = 1) bouncing for 1e7 s in one grid interval: millions of CVODE
    steps and events inside one Model Exchange step (some 13 minutes)."""
    ball = FMUComponent("B", fmu_path("hostile_ball"), interface="model-exchange",
                        tolerance=1e-10)
    ball.set_parameters(e=1.0)
    system = System("integrator")
    system.add_component(ball)
    system.initialize(0.0)
    return system


def step_control_bound(t0: float = 0.0, min_step: float = 1e-9) -> System:
    """A ramp into a gain under a tolerance no step can reach: every step is cut to min_step
    (1e9 steps per second of the run)."""
    ramp = np.array([(t0, 0.0), (t0 + 10.0, 10.0)],
                    dtype=[("time", np.float64), ("u", np.float64)])
    gain = FMUComponent("G", fmus.path("gain"))
    system = System("step control")
    system.add_component(TableSource("src", ramp))
    system.add_component(gain)
    system.add_connection(Connection("src", "u", "G", "u", convert_units=False))
    control = StepControl(rtol=1e-300, atol=1e-300, min_step=min_step)
    system.set_algorithm(JacobiAlgorithm(step_control=control))
    system.initialize(t0)
    return system


class SlowClock(CoSimComponent):
    """x' = 1, each step taking 0.2 s of wall time; rolls back by saving x."""

    def __init__(self) -> None:
        super().__init__("C")
        self.output_specs["x"] = PortSpec("x", PortType.REAL, "out", "s")

    def _initialize_component(self, t0: float) -> None:
        self.x = t0

    def _do_step_internal(self, t: float, dt: float) -> None:
        time.sleep(0.2)
        self.x += dt

    def _update_output_states(self, t=None, event_names=None) -> None:
        self.outputs["x"].set(self.x, t)

    def snapshot_state(self) -> float:
        return self.x

    def restore_state(self, snapshot: float, t: float) -> None:
        self.x = snapshot


def locator_bound() -> System:
    """An event at x = 0.35 in one grid interval of 1 s: some 30 localization trials of 0.2 s
    each."""
    clock = SlowClock()
    clock.add_event_indicator("z", func=lambda c: c.x - 0.35, direction=1)
    clock.add_event_handler("seen", lambda comp, names, t: None)
    system = System("locator")
    system.add_component(clock)
    system.add_event_connection(EventConnection("C", "z", "C", "seen"))
    system.initialize(0.0)
    return system


class Shifted(CoSimComponent):
    """y = 1 + u from t = 0.5 on (before: y = u / 2): its loop with a gain of 1 has no
    solution then, and the loop's iterations go on to max_iter."""

    def __init__(self) -> None:
        super().__init__("S")
        self.input_specs["u"] = PortSpec("u", PortType.REAL, "in")
        self.output_specs["y"] = PortSpec("y", PortType.REAL, "out")
        self.direct_feedthrough = {"y": {"u"}}
        self.now = 0.0

    def _do_step_internal(self, t: float, dt: float) -> None:
        self.now = t + dt

    def _value(self) -> float:
        u = self.inputs["u"].raw()
        return 1.0 + u if self.now >= 0.5 else 0.5 * u

    def _update_output_states(self, t=None, event_names=None) -> None:
        self.outputs["y"].set(self._value(), t)

    def evaluate_outputs(self, inputs, t=None):
        for name, value in inputs.items():
            self.inputs[name].set(value, t)
        return {"y": self._value()}


def loop_bound() -> System:
    gain = FMUComponent("G", fmus.path("gain"))
    system = System("loop")
    system.add_component(gain)
    system.add_component(Shifted())
    system.add_connection(Connection("G", "y", "S", "u", convert_units=False))
    system.add_connection(Connection("S", "y", "G", "u", convert_units=False))
    system.set_algorithm(GaussSeidelAlgorithm())
    system.initialize(0.0)
    system.set_algorithm(GaussSeidelAlgorithm(max_iter=2_000_000_000))
    return system


def stuck_fmu() -> str:
    """tests/fmus/fmi1_stuck, built by meson beside the tests (not installed)."""
    build = build_dir() or ROOT / "build" / "release"
    path = build / "tests" / "fmus" / "fmi1_stuck" / "fmi1_stuck.fmu"
    if not path.is_file():
        pytest.skip(f"the stuck FMI 1.0 test FMU is not built ({path} is missing)")
    return str(path)


def isolation_bound() -> System:
    """An FMI 1.0 FMU in a host process whose fmiDoStep never returns from t = 0.5 on: the
    engine waits for the host."""
    system = System("isolation wait")
    system.add_component(FMUComponent("F", stuck_fmu(), isolated=True))
    system.initialize(0.0)
    return system


# a system whose loop runs long, and the run's tf and dt
LOOPS = {"integrator": (integrator_bound, 1e7, 1e7),
         "step control": (step_control_bound, 2.0, 1.0),
         "locator": (locator_bound, 1.0, 1.0),
         "algebraic loop": (loop_bound, 2.0, 1.0),
         "isolation wait": (isolation_bound, 1.0, 0.1)}


def assert_streamed(path: Path, recorded: object) -> None:
    """Every column of the streamed CSV holds exactly the samples of `recorded` (a result or
    a history), sample for sample."""
    with path.open(newline="") as file:
        header = next(csv.reader(file))
    table = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    assert len(header) > 2
    for column, name in enumerate(header[2:], start=2):
        component, output = name.split(".", 1)
        t, data = recorded[component]  # type: ignore[index]
        assert np.array_equal(table[:, 0], t)
        assert np.array_equal(table[:, column], data[output]), name


@pytest.mark.parametrize("loop", LOOPS)
def test_each_long_loop_stops_within_a_second_of_the_timeout(loop: str, tmp_path: Path):
    build, tf, dt = LOOPS[loop]
    system = build()
    stream = tmp_path / "run.csv"
    started = time.monotonic()
    with pytest.raises(SimulationTimeoutError):
        system.run(0.0, tf, dt, timeout=TIMEOUT, stream_to=stream)
    assert time.monotonic() - started < TIMEOUT + STOP_WITHIN
    history = system.get_history()
    first = next(iter(system.components))
    assert history[first][0][0] == 0.0  # what was recorded stays readable
    assert_streamed(stream, history)


@pytest.mark.parametrize("loop", LOOPS)
def test_ctrl_c_stops_a_long_loop_with_the_partial_result(loop: str, tmp_path: Path):
    build, tf, dt = LOOPS[loop]
    system = build()
    stream = tmp_path / "run.csv"
    timer = threading.Timer(SIGNAL_AFTER, lambda: os.kill(os.getpid(), signal.SIGINT))
    started = time.monotonic()
    timer.start()
    try:
        with pytest.raises(RunInterrupted) as caught:
            system.run(0.0, tf, dt, stream_to=stream)
    finally:
        timer.cancel()
    assert time.monotonic() - started < SIGNAL_AFTER + STOP_WITHIN
    first = next(iter(system.components))
    assert caught.value.partial_result[first][0][0] == 0.0
    assert_streamed(stream, caught.value.partial_result)


SIGTERM_SCRIPT = """
import os, signal, sys, threading, time
import numpy as np
sys.path.insert(0, {tests!r})
from test_run_interruptible import LOOPS, SIGNAL_AFTER
from syssimx.errors import RunTerminated
build, tf, dt = LOOPS[{loop!r}]
system = build()
threading.Timer(SIGNAL_AFTER, lambda: os.kill(os.getpid(), signal.SIGTERM)).start()
started = time.monotonic()
try:
    system.run(0.0, tf, dt, stream_to={stream!r})
except RunTerminated as stop:
    print(time.monotonic() - started, flush=True)
    np.save({kept!r}, {{name: stop.partial_result[name] for name in system.components}},
            allow_pickle=True)
    raise
"""


@pytest.mark.parametrize("loop", LOOPS)
def test_sigterm_stops_a_long_loop_with_the_stream_complete(loop: str, tmp_path: Path):
    """SIGTERM ends the process (status 143) once the run has stopped as for Ctrl-C: the
    partial result and the stream agree."""
    if loop == "isolation wait":
        stuck_fmu()  # a missing test FMU skips here, not in the child
    stream, kept = tmp_path / "run.csv", tmp_path / "partial.npy"
    script = SIGTERM_SCRIPT.format(tests=str(Path(__file__).parent), loop=loop,
                                   stream=str(stream), kept=str(kept))
    child = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                           timeout=60)
    assert child.returncode == 143, child.stderr
    assert float(child.stdout) < SIGNAL_AFTER + STOP_WITHIN
    partial = np.load(kept, allow_pickle=True).item()
    assert partial[next(iter(partial))][0][0] == 0.0
    assert_streamed(stream, partial)


@pytest.mark.parametrize("min_step", [5e-324, 1e-300, 1e-17])
def test_a_min_step_below_the_time_resolution_is_refused(min_step: float):
    with pytest.raises(ConfigurationError, match=r"min_step=.* is below the time resolution"):
        JacobiAlgorithm(step_control=StepControl(min_step=min_step)).validate()


def test_an_ecco_minimum_step_below_the_time_resolution_is_refused_on_reading(tmp_path: Path):
    structure = write_structure(tmp_path, Ecco(1e-3, min_step=5e-324))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the reader's note on ECCO's PI settings
        with pytest.raises(OSPError, match=r"min_step=4\.94066e-324 is below the time "
                           "resolution"):
            read_osp(structure)


def test_time_goes_on_where_its_rounding_is_coarser_than_min_step():
    """min_step 1e-15 from t = 1000 s, where times are 1.1e-13 apart: each step is 2.3e-13."""
    system = step_control_bound(t0=1000.0, min_step=1e-15)
    with pytest.raises(SimulationTimeoutError) as caught:
        system.run(1000.0, 1001.0, 1.0, timeout=0.3)
    assert caught.value.time > 1000.0
