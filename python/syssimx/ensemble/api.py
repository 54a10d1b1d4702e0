"""sweep and monte_carlo: many runs of one system, each member in a Dask worker process."""

from __future__ import annotations

import time
import uuid
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import numpy as np

from ..errors import ConfigurationError, RunInterrupted
from .chunk import Experiment
from .cluster import ensemble_client
from .main_guard import check_main_guard
from .member import MemberResult
from .member_list import MemberList
from .members import ParameterTable, parameter_table
from .result import EnsembleResult
from .runner import MembersInterrupted, run_members
from .sampling import draw
from .system_source import SystemFile, system_source


def sweep(system: Any, parameters: Mapping[str, Iterable[Any]], *, mode: str = "grid",
          t0: float | None = None, tf: float | None = None, dt: float | None = None,
          outputs: Sequence[str] | None = None, client: Any = None,
          scheduler: str | None = None, workers: int | None = None,
          member_timeout: float | None = None, progress: bool = True) -> EnsembleResult:
    """Run `system` once per parameter set, in Dask worker processes.

    Args:
        system: a YAML/JSON system file, or a picklable function returning a System (built
            once per worker process, initialized again for each member: see
            reused_system.py).
        parameters: {"Component.parameter": values}; an input's name holds that input at the
            value.
        mode: "grid" (every combination) or "zip" (the i-th values together).
        t0: the run's start (a system file's `run` entry gives t0, tf and dt when not given).
        tf: the run's end.
        dt: the run's communication step.
        outputs: the "Component.port" names to keep (default: all).
        client: a distributed.Client to run on.
        scheduler: without `client`, a scheduler's address ("tcp://host:8786").
        workers: without either, the processes of an embedded LocalCluster (default one per
            core).
        member_timeout: seconds of wall time a member's run may take (see runner.py for a
            hang inside an FMU).
        progress: a progress bar on stderr.

    Returns:
        The members' results in member order (their parameters, outputs and events).
    """
    return _run("sweep", system, parameter_table(parameters, mode), t0, tf, dt, outputs, client,
                scheduler, workers, member_timeout, progress)


def monte_carlo(system: Any, distributions: Mapping[str, Any], samples: int,
                seed: int | None = None, *, t0: float | None = None, tf: float | None = None,
                dt: float | None = None, outputs: Sequence[str] | None = None,
                client: Any = None, scheduler: str | None = None, workers: int | None = None,
                member_timeout: float | None = None, progress: bool = True) -> EnsembleResult:
    """Run `system` `samples` times with parameters drawn by one seeded generator.

    Args:
        system: as for sweep.
        distributions: {"Component.parameter": a frozen scipy.stats distribution or a
            function (numpy Generator, count) -> values}.
        samples: the number of members.
        seed: the generator's seed (None: a fresh one).

    The other arguments are sweep's.
    """
    return _run("monte_carlo", system, draw(distributions, samples, seed), t0, tf, dt, outputs,
                client, scheduler, workers, member_timeout, progress)


def _run(function: str, system: Any, sets: ParameterTable, t0: float | None, tf: float | None,
         dt: float | None, outputs: Sequence[str] | None, client: Any, scheduler: str | None,
         workers: int | None, member_timeout: float | None, progress: bool) -> EnsembleResult:
    build = system_source(system)
    settings = build.run_settings() if isinstance(build, SystemFile) else {}
    given = {"t0": t0, "tf": tf, "dt": dt}
    settings.update({key: value for key, value in given.items() if value is not None})
    missing = [key for key in given if key not in settings]
    if missing:
        raise ConfigurationError(f"the ensemble's run needs {', '.join(missing)} (given as "
                                 "arguments, or in the system file's 'run' entry)")
    if member_timeout is not None and not (isinstance(member_timeout, int | float)
                                           and member_timeout > 0):
        raise ConfigurationError(f"member_timeout must be a positive number of seconds, got "
                                 f"{member_timeout!r}")
    kept = tuple(outputs) if outputs is not None else None
    ensemble = uuid.uuid4().hex  # its members share one System per worker process
    experiment = Experiment(settings["t0"], settings["tf"], settings["dt"], kept, member_timeout,
                            ensemble)
    if client is None and scheduler is None:  # worker processes started from this script
        check_main_guard(function)
    start = time.perf_counter()
    finished: MemberList | None = None  # every member's result once run_members ends
    try:
        with ensemble_client(client, scheduler, workers) as running_on:
            try:
                finished = run_members(running_on, build, experiment, sets, progress)
            except MembersInterrupted as stop:  # what was finished, on the exception
                finished = stop.results
                raise
    except KeyboardInterrupt as stop:  # in the members, or while the cluster starts or closes
        if finished is None:  # no member had started
            finished = MemberList.of([MemberResult(index, values, "failed",
                                                   "interrupted (Ctrl-C) before it started",
                                                   "KeyboardInterrupt")
                                      for index, values in enumerate(sets)])
        partial = EnsembleResult(finished, list(sets.names), settings["t0"], settings["tf"],
                                 settings["dt"], time.perf_counter() - start)
        done = int(np.count_nonzero(finished.text("error_type") != "KeyboardInterrupt"))
        raise RunInterrupted(f"the ensemble was interrupted: {done} of {len(finished)} "
                             "members had finished (partial_result holds them)",
                             partial) from stop
    return EnsembleResult(finished, list(sets.names), settings["t0"], settings["tf"],
                          settings["dt"], time.perf_counter() - start)
