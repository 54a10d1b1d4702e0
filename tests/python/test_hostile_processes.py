"""Processes, sockets and folders a run leaves (issue 20, items 10, 18, 19, 20): the embedded
cluster listens on loopback only; Ctrl-C and a run's timeout reach an isolated FMU stuck in a
call; extraction folders go on SIGTERM and SIGHUP, and stale ones at the next start; what an
FMU forks ends with its host, or with its sweep member.

The misbehaving FMU is tests/c/hostile (mode 4 never returns from fmi2DoStep, mode 6 forks a
child that lives on and writes its process id to SYSSIMX_TEST_CHILD_PID_FILE)."""

from __future__ import annotations

import functools
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from syssimx import FMUComponent, System, fmus
from syssimx.errors import RunInterrupted, SimulationTimeoutError
from syssimx.fmu.extraction import ORPHAN_AGE, remove_stale_folders
from test_isolation import child_processes, hostile_fmu

ENDLESS_LOOP, FORK_CHILD = 4, 6


def alive(pid: int) -> bool:
    """Whether the process runs (a zombie has ended)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state not in ("Z", "X")


def read_pid(path: Path, timeout: float = 30.0) -> int:
    deadline = time.monotonic() + timeout
    while not (path.is_file() and path.read_text().strip()):
        assert time.monotonic() < deadline, f"{path} was never written"
        time.sleep(0.05)
    return int(path.read_text())


def hung_system() -> tuple[System, FMUComponent]:
    hostile = FMUComponent("H", hostile_fmu(), isolated=True)
    hostile.set_parameters(mode=ENDLESS_LOOP, fail_time=0.25)
    system = System("hung")
    system.add_component(hostile)
    system.initialize(0.0)
    return system, hostile


def test_a_run_timeout_kills_an_isolated_fmu_stuck_in_a_call():
    """Before: only step_timeout could stop it; timeout=2 waited for ever."""
    before = child_processes()
    system, hostile = hung_system()
    started = time.monotonic()
    with pytest.raises(SimulationTimeoutError):
        system.run(0.0, 1.0, 0.1, timeout=2.0)
    assert time.monotonic() - started < 15
    t, _ = system.get_history()["H"]
    assert t[-1] == pytest.approx(0.2)  # the samples before the stuck step are kept
    assert child_processes() <= before  # the host is gone, reaped
    hostile.free()


def test_ctrl_c_kills_an_isolated_fmu_stuck_in_a_call():
    before = child_processes()
    system, hostile = hung_system()
    timer = threading.Timer(1.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    started = time.monotonic()
    try:
        with pytest.raises(RunInterrupted) as caught:
            system.run(0.0, 1.0, 0.1)
    finally:
        timer.cancel()
    assert time.monotonic() - started < 15
    t, _ = caught.value.partial_result["H"]
    assert t[-1] == pytest.approx(0.2)
    assert child_processes() <= before
    hostile.free()


def test_what_an_isolated_fmu_forks_ends_with_its_host(tmp_path: Path,
                                                      monkeypatch: pytest.MonkeyPatch):
    pid_file = tmp_path / "child.pid"
    monkeypatch.setenv("SYSSIMX_TEST_CHILD_PID_FILE", str(pid_file))
    hostile = FMUComponent("H", hostile_fmu(), isolated=True)
    hostile.set_parameters(mode=FORK_CHILD, fail_time=0.05)
    system = System("forks")
    system.add_component(hostile)
    system.initialize(0.0)
    system.run(0.0, 0.2, 0.1)
    child = read_pid(pid_file)
    assert alive(child)
    hostile.free()
    deadline = time.monotonic() + 10
    while alive(child) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not alive(child)


def forking_system(path: str) -> System:
    hostile = FMUComponent("H", path)
    hostile.set_parameters(mode=FORK_CHILD, fail_time=0.05)
    system = System("forks")
    system.add_component(hostile)
    return system


def test_a_sweep_worker_ends_what_a_member_forked(tmp_path: Path,
                                                  monkeypatch: pytest.MonkeyPatch):
    pytest.importorskip("distributed")
    from syssimx.ensemble import sweep

    pid_file = tmp_path / "child.pid"
    monkeypatch.setenv("SYSSIMX_TEST_CHILD_PID_FILE", str(pid_file))  # the workers inherit it
    result = sweep(functools.partial(forking_system, hostile_fmu()), {"H.fail_time": [0.05]},
                   t0=0.0, tf=0.2, dt=0.1, workers=1, progress=False)
    assert result.members[0].ok
    child = read_pid(pid_file)
    deadline = time.monotonic() + 10
    while alive(child) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not alive(child)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="read from Linux's /proc")
def test_a_worker_finds_the_children_any_of_its_threads_forked_but_not_group_leaders():
    """What a sweep worker ends after a task (leftovers.py): a child forked from a thread
    (a member runs on the worker's executor thread), not one leading its own group (an
    isolated FMU's host); the kernel's per-thread lists and the scan of /proc agree."""
    from syssimx.ensemble.leftovers import _listed_children, children

    forked: list[subprocess.Popen[bytes]] = []
    thread = threading.Thread(target=lambda: forked.append(subprocess.Popen(["sleep", "60"])))
    thread.start()
    thread.join()
    leader = subprocess.Popen(["sleep", "60"], start_new_session=True)
    try:
        assert forked[0].pid in children() and leader.pid not in children()
        listed = _listed_children()
        if listed is not None:  # a kernel that keeps the lists
            assert {forked[0].pid, leader.pid} <= listed
    finally:
        for process in (*forked, leader):
            process.kill()
            process.wait()


def listening_addresses(pids: set[int]) -> set[str]:
    import psutil

    addresses = set()
    for pid in pids:
        try:
            connections = psutil.Process(pid).net_connections(kind="inet")
        except (psutil.NoSuchProcess, psutil.AccessDenied):
            continue
        addresses |= {c.laddr.ip for c in connections if c.status == psutil.CONN_LISTEN}
    return addresses


def test_every_socket_of_a_sweep_listens_on_loopback():
    """Before: the dashboard listened on 0.0.0.0."""
    pytest.importorskip("distributed")
    psutil = pytest.importorskip("psutil")
    from syssimx.ensemble import sweep
    from syssimx.ensemble.cluster import ensemble_client

    with ensemble_client(workers=1) as client:
        result = sweep(pendulum_system, {"P.theta0": [0.1, 0.2]}, t0=0.0, tf=0.1, dt=0.05,
                       client=client, progress=False)
        assert all(member.ok for member in result.members)
        me = psutil.Process()
        pids = {me.pid, *(child.pid for child in me.children(recursive=True))}
        addresses = listening_addresses(pids)
    assert addresses, "no listening socket found: the test would prove nothing"
    assert addresses <= {"127.0.0.1", "::1"}, addresses


def pendulum_system() -> System:
    """A pendulum: a member that forks nothing."""
    system = System("pendulum")
    system.add_component(FMUComponent("P", fmus.path("pendulum_euler")))
    return system


@pytest.fixture
def hangup_at_default() -> Iterator[None]:
    """SIGHUP at its default action, as a program started from a terminal has it: started under
    nohup (as a CI runner may start the tests) it is ignored, and the children inherit that;
    syssimx leaves an ignored signal ignored."""
    previous = signal.signal(signal.SIGHUP, signal.SIG_DFL)
    yield
    signal.signal(signal.SIGHUP, previous)


@pytest.mark.parametrize(("signum", "isolated"), [(signal.SIGTERM, False),
                                                  (signal.SIGHUP, False),
                                                  (signal.SIGTERM, True)])
@pytest.mark.usefixtures("hangup_at_default")
def test_a_signal_removes_the_extraction_folders(tmp_path: Path, signum: int, isolated: bool):
    """Before: SIGTERM and SIGHUP left the syssimx_* folders behind."""
    script = textwrap.dedent(f"""
        import sys, tempfile, time
        tempfile.tempdir = {str(tmp_path)!r}
        from syssimx import FMUComponent
        component = FMUComponent("G", {hostile_fmu()!r}, isolated={isolated})
        print(component._unzip_dir, flush=True)
        while True:
            time.sleep(0.05)
    """)
    process = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                               text=True)
    try:
        folder = Path(process.stdout.readline().strip())
        assert folder.is_dir() and folder.parent == tmp_path
        process.send_signal(signum)
        assert process.wait(timeout=60) == -signum
    finally:
        process.kill()
        process.stdout.close()
    assert list(tmp_path.iterdir()) == []


def test_stale_extraction_folders_are_removed_at_start_up(tmp_path: Path):
    """Folders whose owner ended without removing them (SIGKILL) go at the next extraction;
    a live owner's stay, and so do a young folder without an owner file (being made) and one
    owned in another machine or container (its process ids are not ours to judge)."""
    ended = subprocess.Popen(["true"])
    ended.wait()
    stale, live = tmp_path / "syssimx_stale", tmp_path / "syssimx_live"
    old_orphan, young_orphan = tmp_path / "syssimx_old", tmp_path / "syssimx_young"
    elsewhere = tmp_path / "syssimx_elsewhere"
    for folder in (stale, live, old_orphan, young_orphan, elsewhere):
        folder.mkdir()
        (folder / "binary.so").write_bytes(b"x")
    (tmp_path / "syssimx_stale.owner").write_text(f"{ended.pid} 1\n")
    (tmp_path / "syssimx_live.owner").write_text(f"{os.getpid()}\n")
    (tmp_path / "syssimx_elsewhere.owner").write_text(f"{ended.pid} 1 another-host/pid:[1]\n")
    two_days_ago = time.time() - 2 * ORPHAN_AGE
    os.utime(old_orphan, (two_days_ago, two_days_ago))
    removed = remove_stale_folders(tmp_path)
    assert sorted(removed) == [old_orphan, stale]
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "syssimx_elsewhere", "syssimx_elsewhere.owner", "syssimx_live", "syssimx_live.owner",
        "syssimx_young"]


def test_a_killed_process_s_folder_goes_at_the_next_start(tmp_path: Path):
    script = textwrap.dedent(f"""
        import tempfile, time
        tempfile.tempdir = {str(tmp_path)!r}
        from syssimx import FMUComponent, fmus
        component = FMUComponent("G", fmus.path("gain"))
        print(component._unzip_dir, flush=True)
        time.sleep(600)
    """)
    process = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                               text=True)
    try:
        folder = Path(process.stdout.readline().strip())
        process.kill()  # SIGKILL: nothing of the process runs
        process.wait(timeout=60)
    finally:
        process.stdout.close()
    assert folder.is_dir()
    successor = textwrap.dedent(f"""
        import tempfile
        tempfile.tempdir = {str(tmp_path)!r}
        from syssimx import FMUComponent, fmus
        component = FMUComponent("G", fmus.path("gain"))
        print(component._unzip_dir)
    """)
    done = subprocess.run([sys.executable, "-c", successor], capture_output=True, text=True,
                          timeout=120, check=True)
    assert not folder.exists() and done.stdout.strip() != str(folder)
    assert list(tmp_path.iterdir()) == []



def extracting_then_terminated() -> System:
    """A member whose worker ends by SIGTERM after extracting its FMU: nothing of Python's
    exit (atexit) runs in the worker."""
    system = System("terminated")
    system.add_component(FMUComponent("P", fmus.path("pendulum_euler")))
    os.kill(os.getpid(), signal.SIGTERM)
    time.sleep(30)
    return system


def test_a_sweep_removes_what_its_killed_workers_extracted(tmp_path: Path,
                                                           monkeypatch: pytest.MonkeyPatch):
    pytest.importorskip("distributed")
    import tempfile

    from syssimx.ensemble import sweep

    monkeypatch.setenv("TMPDIR", str(tmp_path))  # the workers' temporary folder
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))  # and this process's
    result = sweep(extracting_then_terminated, {"P.theta0": [0.1]}, t0=0.0, tf=0.1, dt=0.05,
                   workers=1, progress=False)
    assert not result.members[0].ok
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith("syssimx_")] == []


def wait_for(path: Path, timeout: float = 120.0) -> None:
    deadline = time.monotonic() + timeout
    while not path.exists() and time.monotonic() < deadline:
        time.sleep(0.05)


def extracting_then_waiting(folder_file: Path, release: Path) -> System:
    """The first worker process extracts its FMU, tells its process id and folder, and waits
    (the test signals it meanwhile); a later one waits before extracting, so that its first
    extraction (which removes stale folders) cannot be what removed the first's."""
    if folder_file.exists():
        wait_for(release)
    system = pendulum_system()
    if not folder_file.exists():
        component = system.components["P"]
        # written whole under another name first: the test reads it as soon as it exists
        partial = folder_file.with_suffix(".partial")
        partial.write_text(f"{os.getpid()} {component._unzip_dir}")
        partial.replace(folder_file)
        wait_for(release)
    return system


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP])
@pytest.mark.usefixtures("hangup_at_default")
def test_a_signal_to_a_sweep_worker_removes_its_extraction_folders(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, signum: int):
    """Before: a worker's folders stayed until the sweep's cluster closed (a member runs on a
    worker thread, where no signal handler can be set)."""
    pytest.importorskip("distributed")
    import tempfile

    from syssimx.ensemble import sweep

    monkeypatch.setenv("TMPDIR", str(tmp_path))  # the workers' temporary folder
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))  # and this process's
    folder_file, release = tmp_path / "folder.txt", tmp_path / "release"
    outcome: list[object] = []
    build = functools.partial(extracting_then_waiting, folder_file, release)
    running = threading.Thread(target=lambda: outcome.append(sweep(
        build, {"P.theta0": [0.1, 0.2]}, t0=0.0, tf=0.1, dt=0.05, workers=1,
        progress=False)))
    running.start()
    try:
        wait_for(folder_file)
        pid_text, folder_text = folder_file.read_text().split()
        folder = Path(folder_text)
        assert folder.is_dir() and folder.parent == tmp_path
        os.kill(int(pid_text), signum)
        deadline = time.monotonic() + 10.0
        while folder.exists() and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not folder.exists() and not Path(f"{folder}.owner").exists()
    finally:
        release.touch()
        running.join(timeout=300)
    assert not running.is_alive() and len(outcome) == 1


FORKING_SCRIPT = """
import os, sys, time
from pathlib import Path
sys.path.insert(0, {tests!r})
from syssimx import FMUComponent, System
from test_isolation import hostile_fmu

hostile = FMUComponent("H", hostile_fmu(), isolated=True)
hostile.set_parameters(mode={mode}, fail_time=0.05)
system = System("forks")
system.add_component(hostile)
system.initialize(0.0)
system.run(0.0, 0.2, 0.1)
child = Path(os.environ["SYSSIMX_TEST_CHILD_PID_FILE"])
while not (child.is_file() and child.read_text().strip()):  # the child has started
    time.sleep(0.01)
"""  # the process ends with the isolated FMU still instantiated


@pytest.mark.parametrize("ending", ["exit", "SIGKILL"])
def test_what_an_isolated_fmu_forks_ends_when_the_engine_process_ends(
        tmp_path: Path, ending: str):
    """Before: the host ended with the engine's process, the child it forked lived on."""
    pid_file = tmp_path / "child.pid"
    script = FORKING_SCRIPT.format(tests=str(Path(__file__).parent), mode=FORK_CHILD)
    if ending == "SIGKILL":
        script += "import os, signal\nos.kill(os.getpid(), signal.SIGKILL)\n"
    engine = subprocess.run([sys.executable, "-c", script], timeout=120,
                            env={**os.environ, "SYSSIMX_TEST_CHILD_PID_FILE": str(pid_file)})
    assert engine.returncode == (0 if ending == "exit" else -signal.SIGKILL)
    child = read_pid(pid_file)
    deadline = time.monotonic() + 10
    while alive(child) and time.monotonic() < deadline:
        time.sleep(0.05)
    if alive(child):
        os.kill(child, signal.SIGKILL)
        pytest.fail("the process the isolated FMU forked outlived the engine's process")
