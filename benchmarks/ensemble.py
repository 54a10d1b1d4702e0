"""Ensembles on Dask against the same members run one after another in this process.

  seed      the seed scenario (examples/pendulum_wall.py, CVODE FMU): 1 s, dt 0.05, one wall
            hit located by rollback; theta0 swept over 0.2..0.6
  coupled   the coupled pendulums (examples/coupled_pendulums.py: two CVODE pendulums and the
            torsion spring FMU, Gauss-Seidel): 2 s, dt 0.01; P1.theta0 swept over 0.2..0.6

Sequential runs each member with the very function a worker runs (syssimx.ensemble.run_member:
take the System, set the parameters, initialize, run, copy the samples out), twice: "fresh"
builds a System per member (what a worker did before it kept its System, and what a loop of
build-and-run does), "one System" keeps one System from member to member as a worker does.
The cluster is the embedded LocalCluster of one worker process per core. Printed, in one run:
- the fixed cost of the embedded cluster: start (scheduler and workers up) and close;
- per scenario and member count: both sequential walls, the sweep's wall on the started
  cluster, the speed-up against each, a member's own time alone (one System) and inside a
  worker (the difference is the cores the workers did not get), Dask's cost per member
  (cluster wall x workers / members minus a member's time in its worker), and the speed-up
  against one System counting the embedded cluster's start and close; CPU seconds per member
  (sequential; the sweep's in this process and the workers) and what their ratio times the
  workers predicts for idle cores. Each row is measured `--repeats` times, sequential and
  cluster in turns, and the best of each is printed;
- memory: each worker's resident size after start and after all sweeps;
- where a seed member's milliseconds go: initialize and run; and what building its System
  costs.

    python benchmarks/ensemble.py [--members 50,200,800] [--workers N] [--repeats 3]
"""

from __future__ import annotations

import argparse
import functools
import math
import os
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
import coupled_pendulums
import pendulum_wall
from syssimx import GaussSeidelAlgorithm, System
from syssimx.ensemble import MemberTask, run_member, sweep
from syssimx.ensemble.cluster import cores, ensemble_client

MB = 1024 * 1024


def seed_system() -> System:
    return pendulum_wall.build("cvode")[0]


SCENARIOS: dict[str, tuple[Callable[[], System], str, float, float]] = {
    "seed": (seed_system, "P.theta0", 1.0, 0.05),
    "coupled": (functools.partial(coupled_pendulums.build, GaussSeidelAlgorithm()),
                "P1.theta0", 2.0, 0.01),
}


def resident_size() -> int:
    import psutil

    return psutil.Process().memory_info().rss


def process_cpu() -> float:
    """CPU seconds of this process (all its threads); run in the workers too."""
    return time.process_time()


def sequential(build: Callable[[], System], name: str, values: np.ndarray, tf: float,
               dt: float, ensemble: str | None) -> tuple[float, float]:
    """Wall and CPU seconds of the members one after another here: on one System (an
    `ensemble` name), or each on a fresh one (None)."""
    start, cpu = time.perf_counter(), process_cpu()
    for index, value in enumerate(values):
        member = run_member(build, MemberTask(index, {name: float(value)}, 0.0, tf, dt,
                                              ensemble=ensemble))
        assert member.ok, member.error
    return time.perf_counter() - start, process_cpu() - cpu


def on_cluster(client: Any, build: Callable[[], System], name: str, values: np.ndarray,
               tf: float, dt: float) -> tuple[float, float, float]:
    """The sweep's wall time, the mean wall time of one member inside its worker, and the CPU
    seconds the sweep took: this process (client, scheduler, nannies) and the workers."""
    workers_cpu = sum(client.run(process_cpu).values())
    start, cpu = time.perf_counter(), process_cpu()
    result = sweep(build, {name: values}, t0=0.0, tf=tf, dt=dt, client=client, progress=False)
    wall, cpu = time.perf_counter() - start, process_cpu() - cpu
    cpu += sum(client.run(process_cpu).values()) - workers_cpu
    assert not result.failed, result.failed[0].error
    return wall, float(np.mean([m.wall_time for m in result.members])), cpu


@dataclass
class Row:
    """One scenario and member count: the best of the repeats of each measurement."""

    scenario: str
    members: int
    fresh: float = math.inf  # sequential wall, a fresh System per member
    fresh_cpu: float = math.inf
    alone: float = math.inf  # sequential wall, one System
    alone_cpu: float = math.inf
    cluster: float = math.inf
    in_worker: float = math.inf
    cluster_cpu: float = math.inf

    def measure(self, client: Any, repeats: int) -> None:
        """Sequential and cluster runs in turns, `repeats` times: the machine's other load
        falls on both alike."""
        build, name, tf, dt = SCENARIOS[self.scenario]
        values = np.linspace(0.2, 0.6, self.members)
        for repeat in range(repeats):
            wall, cpu = sequential(build, name, values, tf, dt, None)
            self.fresh, self.fresh_cpu = min(self.fresh, wall), min(self.fresh_cpu, cpu)
            wall, cpu = sequential(build, name, values, tf, dt, f"{self.scenario}-{repeat}")
            self.alone, self.alone_cpu = min(self.alone, wall), min(self.alone_cpu, cpu)
            wall, in_worker, cpu = on_cluster(client, build, name, values, tf, dt)
            self.cluster, self.in_worker = min(self.cluster, wall), min(self.in_worker,
                                                                         in_worker)
            self.cluster_cpu = min(self.cluster_cpu, cpu)


def member_parts(repeats: int = 50) -> dict[str, float]:
    """Where a seed member's milliseconds go in this process (mean wall times): building its
    System (a worker does it once per ensemble), initialize, run, and a whole member on one
    System (run_member: also setting the parameters and copying the samples out)."""
    build, name, tf, dt = SCENARIOS["seed"]

    def mean(step: Callable[[], object]) -> float:
        start = time.perf_counter()
        for _ in range(repeats):
            step()
        return (time.perf_counter() - start) / repeats

    system = build()
    initialize = run = 0.0
    for _ in range(repeats):  # as a member on one System: reset, initialize, run
        system.reset()
        start = time.perf_counter()
        system.initialize(0.0)
        middle = time.perf_counter()
        system.run(0.0, tf, dt)
        initialize, run = initialize + middle - start, run + time.perf_counter() - middle
    task = MemberTask(0, {name: 0.3}, 0.0, tf, dt, ensemble="parts")
    return {"build": mean(build), "initialize": initialize / repeats, "run": run / repeats,
            "member": mean(lambda: run_member(build, task))}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--members", default="50,200,800",
                        help="member counts for the seed scenario (comma-separated)")
    parser.add_argument("--workers", type=int, default=cores())
    parser.add_argument("--repeats", type=int, default=3,
                        help="measurements of each row, in turns; the best is printed")
    args = parser.parse_args()
    counts = [int(n) for n in args.members.split(",")]
    workers = args.workers

    parts = member_parts()
    load_before = os.getloadavg()[0]
    start = time.perf_counter()
    with ensemble_client(workers=workers) as client:
        started = time.perf_counter() - start
        rss_start = client.run(resident_size)
        rows = [Row("seed", count) for count in counts] + [Row("coupled", 200)]
        for scenario in ("seed", "coupled"):
            build, name, tf, dt = SCENARIOS[scenario]
            on_cluster(client, build, name, np.linspace(0.2, 0.6, workers), tf, dt)  # warm
        for row in rows:
            row.measure(client, args.repeats)
        rss_end = client.run(resident_size)
        closing = time.perf_counter()
    closed = time.perf_counter() - closing

    print(f"{cores()} cores, load average {load_before:.1f} before, {os.getloadavg()[0]:.1f} "
          f"after (other processes share the cores); best of {args.repeats}")
    print(f"embedded cluster, {workers} workers: start {started:.2f} s, close {closed:.2f} s")
    print(f"{'':<17}{'sequential':>21}{'':>10}{'speed-up against':>21}{'per member':>34}")
    print(f"{'scenario':<9}{'members':>8}{'fresh':>10}{'one System':>11}{'cluster':>10}"
          f"{'fresh':>10}{'one System':>11}{'alone':>11}{'in worker':>12}{'scheduling':>12}"
          f"{'embedded':>10}")
    for row in rows:
        per_member = row.alone / row.members
        scheduling = row.cluster * workers / row.members - row.in_worker
        embedded = started + row.cluster + closed
        print(f"{row.scenario:<9}{row.members:>8}{row.fresh:>9.2f}s{row.alone:>10.2f}s"
              f"{row.cluster:>9.2f}s{row.fresh / row.cluster:>9.2f}x"
              f"{row.alone / row.cluster:>10.2f}x{per_member * 1e3:>9.2f}ms"
              f"{row.in_worker * 1e3:>10.2f}ms{scheduling * 1e3:>10.2f}ms"
              f"{row.alone / embedded:>9.2f}x")
    print("(fresh: a System built per member; one System: kept from member to member as a "
          "worker keeps it; per member alone: sequential wall on one System / members; in "
          "worker: a member's own wall time inside its worker, above alone when the workers do "
          "not get a core each; scheduling: cluster wall x workers / members minus in worker, "
          "Dask's cost per member; embedded: sequential wall on one System / (start + cluster "
          "+ close))")
    print(f"\n{'':<17}{'CPU per member':>33}{'cores x CPU ratio against':>30}")
    print(f"{'scenario':<9}{'members':>8}{'fresh':>10}{'one System':>12}{'cluster':>11}"
          f"{'fresh':>15}{'one System':>15}")
    for row in rows:
        print(f"{row.scenario:<9}{row.members:>8}{row.fresh_cpu / row.members * 1e3:>8.2f}ms"
              f"{row.alone_cpu / row.members * 1e3:>10.2f}ms"
              f"{row.cluster_cpu / row.members * 1e3:>9.2f}ms"
              f"{workers * row.fresh_cpu / row.cluster_cpu:>14.2f}x"
              f"{workers * row.alone_cpu / row.cluster_cpu:>14.2f}x")
    print("(CPU seconds, which other load changes less than walls: sequential, and the sweep's "
          "in this process (client, scheduler, nannies) and the workers together; cores x CPU "
          "ratio: the speed-up when the cluster's processes have the cores to themselves)")
    for address in rss_start:
        print(f"worker {address}: resident {rss_start[address] / MB:.0f} MB after start, "
              f"{rss_end[address] / MB:.0f} MB after all sweeps")
    print(f"a seed member on one System in this process: {parts['member'] * 1e3:.2f} ms, of "
          f"which initialize {parts['initialize'] * 1e3:.2f} ms and run {parts['run'] * 1e3:.2f}"
          f" ms; building its System (once per worker and ensemble) "
          f"{parts['build'] * 1e3:.2f} ms")
    print(f"this process (sequential runs, the client and the scheduler): "
          f"{resident_size() / MB:.0f} MB")


if __name__ == "__main__":
    main()
