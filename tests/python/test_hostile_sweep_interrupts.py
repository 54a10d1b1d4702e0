"""Ctrl-C at any moment of a sweep (issue 20, item 17 in the embedded cluster's start and
close): the interrupt is always RunInterrupted with what was finished (nothing, before the
cluster had started), the cluster is closed whole, and `syssimx sweep` exits 130 with its one
line. Before: a Ctrl-C in the cluster's start or close escaped as a bare KeyboardInterrupt and
could leave the cluster's processes running."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import uuid
from pathlib import Path
from typing import Any

import pytest
from syssimx import FMUComponent, System, fmus
from syssimx.errors import RunInterrupted

distributed = pytest.importorskip("distributed")


def pendulum_system() -> System:
    system = System("pendulum")
    system.add_component(FMUComponent("P", fmus.path("pendulum_euler")))
    return system


def sweep_of_two() -> Any:
    from syssimx.ensemble import sweep

    return sweep(pendulum_system, {"P.theta0": [0.1, 0.2]}, t0=0.0, tf=0.1, dt=0.05,
                 workers=1, progress=False)


def test_ctrl_c_while_the_cluster_starts_is_run_interrupted_with_no_member(
        monkeypatch: pytest.MonkeyPatch):
    def interrupted_start(*args: object, **kwargs: object) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(distributed, "LocalCluster", interrupted_start)
    with pytest.raises(RunInterrupted) as caught:
        sweep_of_two()
    members = caught.value.partial_result.members
    assert [(m.ok, m.error_type) for m in members] == [(False, "KeyboardInterrupt")] * 2
    assert "0 of 2 members had finished" in str(caught.value)


def test_a_real_ctrl_c_while_the_cluster_closes_keeps_every_member_and_closes_it(
        monkeypatch: pytest.MonkeyPatch):
    """SIGINT arrives at the start of the close: the close still ends (no nanny left), then
    the interrupt carries the whole result."""
    close = distributed.LocalCluster.close
    workers: list[int] = []

    def interrupted_close(cluster: Any, *args: object, **kwargs: object) -> Any:
        workers.extend(nanny.process.pid for nanny in cluster.workers.values())
        os.kill(os.getpid(), signal.SIGINT)
        return close(cluster, *args, **kwargs)

    monkeypatch.setattr(distributed.LocalCluster, "close", interrupted_close)
    with pytest.raises(RunInterrupted) as caught:
        sweep_of_two()
    members = caught.value.partial_result.members
    assert [m.ok for m in members] == [True, True]
    assert members[1].outputs["P.theta"][0] == pytest.approx(0.2)
    assert "2 of 2 members had finished" in str(caught.value)
    assert len(workers) == 1 and not alive(workers[0])


def alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state not in ("Z", "X")


def processes_marked(marker: str) -> list[int]:
    """The processes whose environment holds `marker` (a sweep's scheduler, nannies and
    workers inherit it)."""
    found = []
    for environ in Path("/proc").glob("[0-9]*/environ"):
        try:
            if marker.encode() in environ.read_bytes():
                found.append(int(environ.parent.name))
        except OSError:
            continue
    return found


def test_ctrl_c_while_syssimx_sweep_starts_its_cluster_exits_130_leaving_nothing(
        tmp_path: Path):
    """A real SIGINT, sent by the process to itself as LocalCluster starts."""
    system_file = tmp_path / "pendulum.yaml"
    system_file.write_text(textwrap.dedent("""
        system: {name: pendulum}
        components:
          - name: P
            fmu: pendulum_euler
        run: {t0: 0.0, tf: 0.1, dt: 0.05}
    """))
    script = tmp_path / "interrupted_sweep.py"
    script.write_text(textwrap.dedent(f"""
        import os, signal, sys
        import distributed
        from syssimx.cli import main

        start = distributed.LocalCluster.__init__

        def interrupted_start(cluster, *args, **kwargs):
            os.kill(os.getpid(), signal.SIGINT)
            start(cluster, *args, **kwargs)

        if __name__ == "__main__":
            distributed.LocalCluster.__init__ = interrupted_start
            sys.exit(main(["sweep", {str(system_file)!r}, "--param", "P.theta0=0.1,0.2",
                           "--workers", "1", "--quiet", "-o", {str(tmp_path / "out.csv")!r}]))
    """))
    marker = f"SYSSIMX_TEST_SWEEP_{uuid.uuid4().hex}"
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                          timeout=300, env={**os.environ, marker: "1"})
    assert done.returncode == 130, done.stderr
    assert "Traceback" not in done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("syssimx: interrupted: the ensemble was "
                                                   "interrupted: 0 of 2"), done.stderr
    assert processes_marked(marker) == []
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith("syssimx_")] == []


def test_ctrl_c_after_the_last_member_keeps_every_member(monkeypatch: pytest.MonkeyPatch):
    """SIGINT while the sweep unsubscribes from its members' announcements, after both had
    finished. Before: RunInterrupted with "0 of 2 members had finished", both marked failed."""
    from syssimx.ensemble import runner

    def interrupted_close(ensemble: Any) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(runner._Ensemble, "close", interrupted_close)
    with pytest.raises(RunInterrupted) as caught:
        sweep_of_two()
    members = caught.value.partial_result.members
    assert [m.ok for m in members] == [True, True]
    assert members[1].outputs["P.theta"][0] == pytest.approx(0.2)
    assert "2 of 2 members had finished" in str(caught.value)


def test_ctrl_c_keeps_members_finished_on_the_workers_but_not_yet_taken(
        monkeypatch: pytest.MonkeyPatch):
    """SIGINT while the sweep waits for its next result, once the members' task has finished
    and its result has arrived. Before: those members were marked failed."""
    import time

    def interrupted_next(completed: Any) -> Any:
        while completed.queue.empty():
            time.sleep(0.01)
        raise KeyboardInterrupt

    monkeypatch.setattr(distributed.as_completed, "__next__", interrupted_next)
    with pytest.raises(RunInterrupted) as caught:
        sweep_of_two()
    members = caught.value.partial_result.members
    assert members[0].ok
    assert members[0].outputs["P.theta"][0] == pytest.approx(0.1)
    done = sum(m.ok for m in members)
    assert f"{done} of 2 members had finished" in str(caught.value)
