"""Sweeps and Monte Carlo runs on a real LocalCluster of 2 worker processes: the seed pendulum's
event times against the exact quarter period for every member, members bit-identical to the
same System run in this process, each FMU file loaded once per worker, the embedded cluster."""

from __future__ import annotations

import gc
import os
import sys
from collections.abc import Iterator

import coupled_pendulums as coupled_pendulums_example
import numpy as np
import pytest

pytest.importorskip("distributed")
pytest.importorskip("xarray")
import pendulum_wall
import xarray as xr
from scipy import stats
from scipy.special import ellipk
from syssimx import (
    ConfigurationError,
    JacobiAlgorithm,
    System,
    fmus,
)
from syssimx.ensemble import EnsembleResult, monte_carlo, sweep
from syssimx.ensemble.cluster import ensemble_client
from syssimx.ensemble.loaded_fmus import loaded_fmus

M, L, G, INERTIA = 40.0, 0.6, 9.81, 20.0
THETA0S = [0.2, 0.35, 0.5, 0.65]


def quarter_period(theta0: float) -> float:
    """First wall hit of the pendulum released from rest at theta0 (elliptic integral)."""
    return float(ellipk(np.sin(theta0 / 2) ** 2) / np.sqrt(M * G * L / INERTIA))


@pytest.fixture(scope="module")
def client() -> Iterator[object]:
    with ensemble_client(workers=2) as running:
        yield running


def seed_pendulum() -> System:
    """The seed scenario, CVODE at rtol 1e-10, events located to 1e-9 (examples/pendulum_wall)."""
    return pendulum_wall.build("cvode")[0]


def coupled_pendulums() -> System:
    """Two CVODE pendulums and the torsion spring, Jacobi (examples/coupled_pendulums)."""
    return coupled_pendulums_example.build(JacobiAlgorithm(), rtol=1e-8)


def in_process(build, parameters: dict[str, float], tf: float, dt: float):
    """The same function's System, parameters set and run here, the usual way."""
    system = build()
    for name, value in parameters.items():
        component, parameter = name.split(".", 1)
        system.components[component].set_parameters(**{parameter: value})
    system.initialize(0.0)
    return system.run(0.0, tf, dt)


def test_seed_pendulum_sweep_hits_the_wall_at_the_exact_quarter_period(client) -> None:
    result = sweep(seed_pendulum, {"P.theta0": THETA0S}, t0=0.0, tf=1.0, dt=0.05,
                   client=client, progress=False)
    assert [m.status for m in result.members] == ["ok"] * 4
    for member, theta0 in zip(result.members, THETA0S, strict=True):
        assert member.parameters == {"P.theta0": theta0}
        (t, micro, source), = member.events
        assert (micro, source) == (0, "P.wall_hit")
        assert abs(t - quarter_period(theta0)) < 1e-9, (theta0, t - quarter_period(theta0))
    assert list(result.dataset["P.theta0"].values) == THETA0S
    assert list(result.dataset["event_source"].values[:, 0]) == ["P.wall_hit"] * 4
    # the member's own axis keeps the event instant twice (before and after handling)
    assert (result.dataset["samples"].values == 21 + 2).all()


def test_members_are_bit_identical_to_the_same_system_run_in_process(client) -> None:
    result = sweep(seed_pendulum, {"P.theta0": [0.3, 0.5]}, t0=0.0, tf=1.0, dt=0.05,
                   client=client, progress=False)
    for member in result.members:
        here = in_process(seed_pendulum, member.parameters, 1.0, 0.05)
        t, values = here["P"]
        assert np.array_equal(member.time, t)
        assert np.array_equal(member.micro, here.micro)
        for port, series in values.items():
            assert np.array_equal(member.outputs[f"P.{port}"], series), port
        assert member.events == tuple((e.t, e.micro, f"{e.component}.{e.event}")
                                      for e in here.events)
        assert member.statistics["do_step_calls"] == here.statistics.do_step_calls
        assert member.worker.split(":")[1] != str(os.getpid())  # it ran in another process


def test_monte_carlo_of_the_coupled_pendulums_matches_in_process_runs(client) -> None:
    distributions = {"P1.theta0": stats.uniform(0.2, 0.3), "Spring.k": stats.norm(100, 5)}
    result = monte_carlo(coupled_pendulums, distributions, 3, seed=11, t0=0.0, tf=0.5,
                         dt=0.01, outputs=["P1.theta", "P2.theta"], client=client,
                         progress=False)
    again = monte_carlo(coupled_pendulums, distributions, 3, seed=11, t0=0.0, tf=0.5,
                        dt=0.01, outputs=["P1.theta", "P2.theta"], client=client,
                        progress=False)
    assert [m.parameters for m in result.members] == [m.parameters for m in again.members]
    assert list(result.dataset.data_vars)[:2] == ["P1.theta", "P2.theta"]
    for member in result.members:
        here = in_process(coupled_pendulums, member.parameters, 0.5, 0.01)
        assert np.array_equal(member.outputs["P2.theta"], here["P2"][1]["theta"])
        assert member.outputs.keys() == {"P1.theta", "P2.theta"}
    assert np.array_equal(result.grid()["P2.theta"].values, again.grid()["P2.theta"].values)


def worker_fmus() -> dict[str, tuple[int, int]]:
    """Run in a worker: {FMU file: (members that used it, extractions)} of that process."""
    return loaded_fmus.summary()


def test_each_worker_extracts_each_fmu_file_once(client) -> None:
    before = client.run(worker_fmus)
    sweep(seed_pendulum, {"P.theta0": np.linspace(0.2, 0.6, 6)}, t0=0.0, tf=0.2, dt=0.05,
          client=client, progress=False)
    after = client.run(worker_fmus)
    path = str(fmus.path("pendulum_cvode"))
    assert sum(report.get(path, (0, 0))[0] for report in after.values()) - sum(
        report.get(path, (0, 0))[0] for report in before.values()) == 6, after
    assert all(report[path][1] == 1 for report in after.values() if path in report)


BUILT: list[int] = []  # filled in the worker processes: one entry per System built there


def counted_seed_pendulum() -> System:
    BUILT.append(os.getpid())
    return seed_pendulum()


def systems_built() -> int:
    """Run in a worker: how many Systems counted_seed_pendulum built in that process."""
    return len(BUILT)


def test_each_worker_builds_the_system_once_per_ensemble(client) -> None:
    before = client.run(systems_built)
    result = sweep(counted_seed_pendulum, {"P.theta0": np.linspace(0.2, 0.6, 12)}, t0=0.0,
                   tf=0.2, dt=0.05, client=client, progress=False)
    after = client.run(systems_built)
    assert not result.failed
    built = sum(after.values()) - sum(before.get(worker, 0) for worker in after)
    assert built == len({member.worker for member in result.members})  # 1 or 2, not 12


def test_outputs_written_as_netcdf_and_csv_read_back_equal(client, tmp_path) -> None:
    result = sweep(seed_pendulum, {"P.theta0": [0.3, 0.5]}, t0=0.0, tf=0.6, dt=0.1,
                   outputs=["P.theta"], client=client, progress=False)
    assert list(result.output_names) == ["P.theta"]
    netcdf = xr.open_dataset(result.write(tmp_path / "out.nc"))
    np.testing.assert_array_equal(netcdf["P.theta"].values, result.dataset["P.theta"].values)
    np.testing.assert_array_equal(netcdf["time"].values, result.dataset["time"].values)
    assert list(netcdf["status"].values) == ["ok", "ok"]
    import pandas as pd

    table = pd.read_csv(result.write(tmp_path / "out.csv"))
    assert len(table) == sum(m.time.size for m in result.members)
    assert table[table.member == 1]["P.theta"].tolist() == result.members[1].outputs[
        "P.theta"].tolist()


def test_embedded_cluster_without_a_client_and_no_bar_off_a_terminal(capsys) -> None:
    result = sweep(seed_pendulum, {"P.theta0": [0.4, 0.5]}, t0=0.0, tf=0.6, dt=0.05,
                   workers=2)
    assert isinstance(result, EnsembleResult) and not result.failed
    assert "\r" not in capsys.readouterr().err  # stderr is no terminal: no bar frames
    assert abs(result.members[1].events[0][0] - quarter_period(0.5)) < 1e-9


def test_a_scheduler_address_runs_there_and_threaded_workers_are_refused(client) -> None:
    result = sweep(seed_pendulum, {"P.theta0": [0.5]}, t0=0.0, tf=0.6, dt=0.05,
                   scheduler=client.scheduler.address, progress=False)
    assert abs(result.members[0].events[0][0] - quarter_period(0.5)) < 1e-9
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=2, dashboard_address=":0") as threaded, \
            Client(threaded) as threaded_client, pytest.raises(
                ConfigurationError, match=r"ensemble workers must run one thread each \(start "
                                          r"them with 'dask worker ADDRESS --nthreads 1'\); "
                                          r"threads per worker: \{'tcp://"):
        sweep(seed_pendulum, {"P.theta0": [0.5]}, t0=0.0, tf=0.6, dt=0.05,
              client=threaded_client, progress=False)


SET_BEFORE_THE_CLUSTER: list[int] = []  # a forked worker has it as this process had it


def set_before_the_cluster() -> list[int]:
    return SET_BEFORE_THE_CLUSTER


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="workers fork on Linux only")
def test_the_embedded_cluster_forks_its_workers() -> None:
    """A spawned worker imports this module anew (an empty list); a forked one starts with what
    this process had when the cluster started."""
    SET_BEFORE_THE_CLUSTER.append(os.getpid())
    try:
        with ensemble_client(workers=1) as running:
            assert list(running.run(set_before_the_cluster).values()) == [[os.getpid()]]
    finally:
        SET_BEFORE_THE_CLUSTER.clear()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="workers fork on Linux only")
def test_forked_workers_keep_this_process_s_objects_frozen_and_this_process_does_not() -> None:
    """The objects inherited from the fork stay out of a worker's collections (copy-on-write);
    here they are collected as before, once the cluster has started."""
    assert gc.get_freeze_count() == 0
    with ensemble_client(workers=1) as running:
        assert gc.get_freeze_count() == 0
        [frozen] = running.run(gc.get_freeze_count).values()
        assert frozen > 1000


def test_a_probed_ensemble_s_members_and_dataset_are_those_run_in_process(client) -> None:
    """40 members on 2 workers: a probe chunk of 4 members per worker, then chunks sized by
    its members' cost; every member, and the dataset built from the blocks, bit-identical to
    the same System run here."""
    from syssimx.ensemble.runner import PROBED_FROM

    values = np.linspace(0.2, 0.6, 40)
    assert len(values) >= PROBED_FROM * 2
    result = sweep(seed_pendulum, {"P.theta0": values}, t0=0.0, tf=0.3, dt=0.05,
                   client=client, progress=False)
    assert not result.failed and [m.index for m in result.members] == list(range(40))
    dataset = result.dataset
    for k in (0, 7, 8, 23, 39):  # probe members, the first after the probe, later ones
        here = in_process(seed_pendulum, {"P.theta0": float(values[k])}, 0.3, 0.05)
        t, series = here["P"]
        assert np.array_equal(dataset["time"].values[k, :t.size], t)
        assert np.array_equal(dataset["P.theta"].values[k, :t.size], series["theta"])
        assert np.array_equal(result.members[k].outputs["P.omega"], series["omega"])
    assert list(dataset["P.theta0"].values) == list(values)


def test_a_later_ensemble_of_the_same_system_and_run_skips_the_probe(client, monkeypatch) -> None:
    """The probe's member cost is remembered for the system and run: the same 40 members
    again are cut by it at once (one submission covering every member, no probe of 4 per
    worker first), and come out bit-identical."""
    from syssimx.ensemble import runner

    submitted: list[list[int]] = []
    submit = runner._Ensemble._submit

    def recording(ensemble, chunks, *rest):
        submitted.append([len(chunk) for chunk in chunks])
        return submit(ensemble, chunks, *rest)

    monkeypatch.setattr(runner._Ensemble, "_submit", recording)
    monkeypatch.setattr(runner, "_COSTS", {})
    values = np.linspace(0.2, 0.6, 40)
    first = sweep(seed_pendulum, {"P.theta0": values}, t0=0.0, tf=0.2, dt=0.05,
                  client=client, progress=False)
    assert submitted[0] == [runner.PROBE] * 2 and len(submitted) == 2
    submitted.clear()
    again = sweep(seed_pendulum, {"P.theta0": values}, t0=0.0, tf=0.2, dt=0.05,
                  client=client, progress=False)
    assert len(submitted) == 1 and sum(submitted[0]) == 40
    assert not first.failed and not again.failed
    assert first.dataset.drop_vars(["wall_time", "worker"]).identical(
        again.dataset.drop_vars(["wall_time", "worker"]))
    other_run = sweep(seed_pendulum, {"P.theta0": values}, t0=0.0, tf=0.25, dt=0.05,
                      client=client, progress=False)
    assert not other_run.failed and submitted[1] == [runner.PROBE] * 2  # another run: probed


async def heartbeat_interval(dask_worker) -> float:
    """Seconds to the worker's next heartbeat after one now (the scheduler's reply sets it)."""
    await dask_worker.heartbeat()
    return dask_worker.periodic_callbacks["heartbeat"].callback_time / 1000


def test_the_quiet_housekeeping_is_the_embedded_cluster_s_alone(client) -> None:
    """The embedded cluster's workers heartbeat every HEARTBEAT seconds and its scheduler runs
    no active memory manager; a cluster of the user's own keeps Dask's settings through a
    sweep on it."""
    from distributed import Client, LocalCluster
    from syssimx.ensemble.cluster import HEARTBEAT

    assert set(client.run(heartbeat_interval).values()) == {HEARTBEAT}
    assert not client.cluster.scheduler.extensions["amm"].running
    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=":0") as theirs, \
            Client(theirs) as their_client:
        result = sweep(seed_pendulum, {"P.theta0": [0.5]}, t0=0.0, tf=0.3, dt=0.05,
                       client=their_client, progress=False)
        assert not result.failed
        assert set(their_client.run(heartbeat_interval).values()) == {0.5}  # Dask's own
        assert theirs.scheduler.extensions["amm"].running
