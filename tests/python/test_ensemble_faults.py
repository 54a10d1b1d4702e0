"""Faults in ensemble members on a real LocalCluster of 2 worker processes: a failing FMU, a
Python exception, a run past member_timeout (in the engine's loop, and stuck inside an FMU
call), a segfault that kills the worker process. Each is reported on its member with the
reason; every other member's result is kept and the sweep finishes.

The misbehaving FMU (tests/c/hostile) is built by meson beside the tests, like for
test_isolation.py."""

from __future__ import annotations

import functools
from collections.abc import Iterator

import numpy as np
import pytest
from fixture_fmus import fmu_path

pytest.importorskip("distributed")
pytest.importorskip("xarray")
import pendulum_wall
from syssimx import Connection, FMUComponent, System, fmus
from syssimx.ensemble import sweep
from syssimx.ensemble.cluster import ensemble_client
from syssimx.ensemble.runner import chunk_size
from test_isolation import hostile_fmu

BEHAVE, SEGFAULT, ENDLESS_LOOP = 0, 1, 4


@pytest.fixture(scope="module")
def client() -> Iterator[object]:
    with ensemble_client(workers=2) as running:
        yield running


def failing_system() -> System:
    """The failing FMU (y = u) fed a constant input: it fails after fail_time as `failure`
    says (0 error, 1 fatal, 2 discard, 3 read failure, 4 NaN, which stops the run where it
    reaches an input: y feeds a gain)."""
    failing = FMUComponent("F", fmu_path("failing"))
    failing.set_inputs({"u": 2.0})
    system = System("failing")
    system.add_component(failing)
    system.add_component(FMUComponent("G", fmus.path("gain")))
    system.add_connection(Connection("F", "y", "G", "u", convert_units=False))
    return system


def hostile_system(path: str) -> System:
    hostile = FMUComponent("H", path)
    hostile.set_parameters(fail_time=0.05)
    system = System("hostile")
    system.add_component(hostile)
    return system


def refusing_wall(component: FMUComponent, events: list[str], t: float) -> None:
    raise RuntimeError(f"the wall refuses the pendulum at t={t:.6f}")


def pendulum_with_a_raising_handler() -> System:
    system, pendulum = pendulum_wall.build("euler")
    pendulum.event_handlers["omega_invert"] = [refusing_wall]
    return system


def test_failing_fmu_members_report_each_failure_and_keep_their_samples(client) -> None:
    result = sweep(failing_system, {"F.failure": [0, 1, 2, 3, 4, 0],
                                    "F.fail_time": [0.5, 0.5, 0.5, 0.5, 0.5, 2.0]},
                   mode="zip", t0=0.0, tf=1.0, dt=0.1, client=client, progress=False)
    statuses = [m.status for m in result.members]
    assert statuses == ["failed"] * 5 + ["ok"]
    errors = [m.error for m in result.members[:5]]
    assert "the simulation passed fail_time (a deliberate failure)" in errors[0]
    assert errors[0].startswith("SimulationError: component 'F': fmi2DoStep failed at t=0.5 "
                                "with status fmi2Error")
    assert "a deliberate fatal failure" in errors[1]
    assert "fmi2LastSuccessfulTime" in errors[2]
    assert "a deliberate read failure" in errors[3]
    assert "output 'y' is" in errors[4] and "nan" in errors[4].lower()
    for member in result.members[:5]:
        assert member.time[-1] <= 0.5 + 1e-12  # what they recorded before failing
        assert np.all(member.outputs["F.y"][member.time <= 0.5] == 2.0)
    assert result.members[5].time[-1] == 1.0 and result.members[5].statistics["macro_steps"] \
        == 10
    assert list(result.dataset["status"].values) == statuses


def test_an_exception_in_a_handler_fails_only_its_member(client) -> None:
    # from -0.5 the pendulum swings up through the wall's angle: no falling crossing, no call
    result = sweep(pendulum_with_a_raising_handler, {"P.theta0": [0.5, -0.5]}, t0=0.0,
                   tf=1.0, dt=0.05, client=client, progress=False)
    raised, calm = result.members
    assert raised.status == "failed" and raised.error_type == "SimulationError"
    assert "RuntimeError: the wall refuses the pendulum at t=0.46508" in raised.error
    assert calm.ok and calm.time[-1] == 1.0


def slow_pendulum() -> System:
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    system = System("slow pendulum")
    system.add_component(pendulum)
    return system


def test_a_run_past_member_timeout_stops_in_the_engine_and_keeps_its_samples(client) -> None:
    # euler_step_size 1e-8 makes each step of 1e-3 a million substeps: far past 1 s of wall
    result = sweep(slow_pendulum, {"P.euler_step_size": [1e-4, 1e-8]}, t0=0.0, tf=2.0,
                   dt=1e-3, member_timeout=1.0, client=client, progress=False)
    quick, slow = result.members
    assert quick.ok and quick.time[-1] == 2.0
    assert slow.error_type == "SimulationTimeoutError"
    assert "1 s" in slow.error or "timeout" in slow.error.lower(), slow.error
    assert 0.0 < slow.time[-1] < 2.0


def test_a_member_stuck_inside_an_fmu_call_is_stopped_by_restarting_its_worker(client) -> None:
    build = functools.partial(hostile_system, hostile_fmu())
    result = sweep(build, {"H.mode": [BEHAVE, ENDLESS_LOOP, BEHAVE, BEHAVE]}, t0=0.0, tf=0.2,
                   dt=0.01, member_timeout=1.0, client=client, progress=False)
    assert [m.status for m in result.members] == ["ok", "failed", "ok", "ok"]
    stuck = result.members[1]
    assert stuck.error_type == "MemberTimeout"
    assert stuck.error.startswith("MemberTimeout: still running 2 s after it started "
                                  "(member_timeout=1 s), stuck where the run's timeout cannot "
                                  "stop it; its worker process ")
    assert all(m.time[-1] == 0.2 for m in result.members if m.ok)
    client.wait_for_workers(2, timeout=60)  # the restarted worker is back


def test_a_segfault_fails_its_member_with_the_signal_and_the_sweep_finishes(client) -> None:
    modes = [BEHAVE] * 16
    modes[5] = SEGFAULT
    # chunks of 2 or 3: the crash takes members 6 and 7 down with it, each then rerun alone
    assert chunk_size(len(modes), 2) == 3
    build = functools.partial(hostile_system, hostile_fmu())
    result = sweep(build, {"H.mode": modes}, t0=0.0, tf=0.2, dt=0.01, client=client,
                   progress=False)
    assert [m.index for m in result.members if not m.ok] == [5], [m.error for m in result]
    crashed = result.members[5]
    assert crashed.error_type == "WorkerDied"
    assert crashed.error.startswith("WorkerDied: the worker process ")
    assert crashed.error.endswith("died while running this member, of signal 11 (SIGSEGV, "
                                  "Segmentation fault)")
    assert all(m.outputs["H.y"][-1] == 0.2 for m in result.members if m.ok)
