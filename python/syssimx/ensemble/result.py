"""An ensemble's results: per-member outcomes, an xarray Dataset, a tidy table, files.

Members of a hybrid system have samples at their own event instants (two per event: before
and after handling), so members rarely share one time axis. `dataset` keeps every member's own
samples: dimensions member x sample, with `time` and `micro` as (member, sample) coordinates
(shorter members padded with NaN and micro -1). `grid()` gives the member x time view on the
common grid t0 + k*dt (tf last), the sample taken at each grid time before any event there;
event instants between grid points are left out of that view only.
"""

from __future__ import annotations

import importlib.util
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ConfigurationError, MissingDependencyError
from ..extras import install_hint, require
from .member import STATISTICS, MemberResult
from .member_list import MemberList

WRITERS = (".csv", ".parquet", ".nc")
# xarray's engines for .nc files, in order of preference, and the modules each needs
NETCDF_ENGINES = (("scipy", ("scipy",)), ("netcdf4", ("netCDF4",)),
                  ("h5netcdf", ("h5netcdf", "h5py")))
MEMBERS_SHOWN = 10  # members listed in a notebook's table; the rest are counted


class EnsembleResult:
    """`members` in member order; `dataset`, `grid()`, `events`, `to_dataframe()`, `write()`."""

    def __init__(self, members: Sequence[MemberResult], parameters: Sequence[str], t0: float,
                 tf: float, dt: float, wall_time: float) -> None:
        # a sweep's MemberList cuts a member's result from its block when first asked for
        self.members = members if isinstance(members, MemberList) \
            else MemberList.of(list(members))
        self.parameters = list(parameters)
        self.t0, self.tf, self.dt, self.wall_time = t0, tf, dt, wall_time
        self._dataset: Any = None

    def __repr__(self) -> str:
        return (f"EnsembleResult({len(self.members)} members, {len(self.failed)} failed, "
                f"parameters={self.parameters}, wall_time={self.wall_time:.3g} s)")

    def _repr_html_(self) -> str:
        """Members, failures and parameters, then the first members' values and status."""
        from ..system.result_display import html_table

        summary = html_table(("members", "ok", "failed", "parameters", "t0 [s]", "tf [s]",
                              "dt [s]", "wall time [s]"),
                             [(len(self), len(self) - len(self.failed), len(self.failed),
                               ", ".join(self.parameters), self.t0, self.tf, self.dt,
                               f"{self.wall_time:.3g}")])
        shown = self.members[:MEMBERS_SHOWN]
        rows: list[list[Any]] = [[m.index, *(m.parameters[p] for p in self.parameters),
                                  m.status, m.time.size, m.error or ""] for m in shown]
        if len(self.members) > MEMBERS_SHOWN:
            rows.append(["…", *([""] * len(self.parameters)), "",
                         "", f"{len(self.members) - MEMBERS_SHOWN} more"])
        members = html_table(("member", *self.parameters, "status", "samples", "error"), rows)
        return f"<div>{summary}{members}</div>"

    def __len__(self) -> int:
        return len(self.members)

    def __getitem__(self, index: int) -> MemberResult:
        return self.members[index]

    @property
    def failed(self) -> list[MemberResult]:
        """The members that did not complete, each with its status, reason and the samples it
        recorded before."""
        return [self.members[int(index)]
                for index in np.flatnonzero(self.members.text("status") != "ok")]

    @property
    def output_names(self) -> list[str]:
        """Every "Component.port" recorded by some member, in first-seen order."""
        return self.members.output_names()

    # ------------------------------------------------------------------ xarray
    @property
    def dataset(self) -> Any:
        """The results as an xarray Dataset, member x sample.

        Each member keeps its own time axis (see the module's description); the parameters are
        member coordinates, the events member x event variables, and per member there are its
        status, error, termination, worker, wall time and run statistics (-1 for a member whose
        run did not complete)."""
        if self._dataset is None:
            self._dataset = self._build_dataset()
        return self._dataset

    def _build_dataset(self) -> Any:
        xr = require("xarray", "EnsembleResult.dataset")

        count = len(self.members)
        time, micro, outputs = self.members.padded(self.output_names)
        event_time, event_micro, event_source = _at_least_one_event(*self.members.events())
        member_vars: dict[str, Any] = {
            **{name: ("member", self.members.text(name))
               for name in ("status", "error", "termination", "worker")},
            **{name: ("member", self.members.numbers(name)) for name in ("wall_time", "samples")},
            **{statistic: ("member", self.members.statistic(statistic))
               for statistic in STATISTICS},
        }
        coords: dict[str, Any] = {
            "member": np.arange(count),
            "time": (("member", "sample"), time),
            "micro": (("member", "sample"), micro),
            **{name: ("member", self.members.parameters.column(name))
               for name in self.parameters},
        }
        return xr.Dataset(
            {**{name: (("member", "sample"), values) for name, values in outputs.items()},
             "event_time": (("member", "event"), event_time),
             "event_micro": (("member", "event"), event_micro),
             "event_source": (("member", "event"), event_source),
             **member_vars},
            coords=coords,
            attrs={"t0": self.t0, "tf": self.tf, "dt": self.dt})

    def grid(self) -> Any:
        """member x time on the common grid t0 + k*dt (tf last): at each grid time the first
        sample a member recorded there (before an event handled at that instant); NaN where a
        member has no sample (it failed or stopped earlier)."""
        xr = require("xarray", "EnsembleResult.grid")

        grid = _grid(self.t0, self.tf, self.dt)
        tolerance = 1e-9 * self.dt
        values = {name: np.full((len(self.members), grid.size), np.nan)
                  for name in self.output_names}
        # every member's samples at once, from the padded arrays (NaN past a member's last)
        time, _, outputs = self.members.padded(self.output_names)
        position = np.clip(np.searchsorted(grid, time), 1, grid.size - 1)
        nearest = np.where(np.abs(grid[position - 1] - time) <= np.abs(grid[position] - time),
                           position - 1, position)
        members, samples = np.nonzero(np.abs(grid[nearest] - time) <= tolerance)
        columns = nearest[members, samples]
        # the first sample of a member at each grid time: the one recorded before an event
        # there (np.nonzero gives each member's samples in order)
        _, first = np.unique(members * grid.size + columns, return_index=True)
        members, samples, columns = members[first], samples[first], columns[first]
        for name, series in outputs.items():
            values[name][members, columns] = series[members, samples]
        parameters = {name: ("member", self.members.parameters.column(name))
                      for name in self.parameters}
        return xr.Dataset({name: (("member", "time"), data) for name, data in values.items()},
                          coords={"member": np.arange(len(self.members)), "time": grid,
                                  **parameters})

    # ------------------------------------------------------------------ tables
    def to_dataframe(self) -> Any:
        """The tidy table: one row per member and sample; columns member, the parameters,
        status, time, micro and one per output. A member that recorded nothing has one row
        (its status and error) with NaN samples. Made from the members' padded arrays, no
        table per member (2000 seed members: about 2.6 s before, 0.05 s)."""
        pd = require("pandas", "EnsembleResult.to_dataframe")

        members, count = self.members, len(self.members)
        time, micro, outputs = members.padded(self.output_names)
        if time.shape[1] == 0:  # no member recorded a sample: each has its one row of NaN
            time, micro = np.full((count, 1), np.nan), np.full((count, 1), -1, dtype=np.int64)
            outputs = {name: np.full((count, 1), np.nan) for name in outputs}
        rows = np.maximum(members.numbers("samples"), 1)
        member = np.repeat(np.arange(count), rows)
        sample = np.arange(int(rows.sum())) - np.repeat(np.cumsum(rows) - rows, rows)
        columns: dict[str, Any] = {"member": member}
        for name in self.parameters:
            columns[name] = members.parameters.column(name)[member]
        for name in ("status", "error"):
            columns[name] = members.text(name)[member]
        columns["time"], columns["micro"] = time[member, sample], micro[member, sample]
        for name in self.output_names:
            columns[name] = outputs[name][member, sample]
        return pd.DataFrame(columns)

    @property
    def events(self) -> Any:
        """The located events as a DataFrame, one row per member and event (member, the
        parameters, time, micro, source)."""
        pd = require("pandas", "EnsembleResult.events")

        rows = [{"member": m.index, **{n: m.parameters[n] for n in self.parameters},
                 "time": t, "micro": micro, "source": source}
                for m in self.members for t, micro, source in m.events]
        return pd.DataFrame(rows, columns=["member", *self.parameters, "time", "micro",
                                           "source"])

    def write(self, path: str | Path) -> Path:
        """Write by suffix: .csv and .parquet the tidy table (parquet needs pyarrow or
        fastparquet), .nc the dataset (netCDF, by netcdf_engine())."""
        from ..atomic_file import atomic_path

        target = Path(path)
        suffix = target.suffix.lower()
        if suffix not in WRITERS:
            raise ConfigurationError(f"{target}: unknown result format {suffix!r}; use one of "
                                     f"{', '.join(WRITERS)}")
        with atomic_path(target) as temporary:  # whole or not at all
            if suffix == ".csv":
                self.to_dataframe().to_csv(temporary, index=False)
            elif suffix == ".parquet":
                try:
                    self.to_dataframe().to_parquet(temporary, index=False)
                except ImportError as error:
                    raise ConfigurationError(f"{target}: writing parquet needs pyarrow or "
                                             f"fastparquet ({error}); write .csv or .nc "
                                             "instead") from error
            else:
                self._netcdf_dataset().to_netcdf(temporary, engine=netcdf_engine())
        return target

    def _netcdf_dataset(self) -> Any:
        """netCDF holds fixed-width strings, not Python objects; a name NetCDF or scipy cannot
        hold as it is (a '/', a line break, beyond ASCII) is encoded, itself kept as the
        variable's long_name (streaming.netcdf_names)."""
        from ..streaming.netcdf_names import netcdf_name

        dataset = self.dataset.copy()
        for name in ("status", "error", "termination", "worker", "event_source"):
            dataset[name] = dataset[name].astype(str)
        for name in self.parameters:
            if dataset[name].dtype == object:
                dataset[name] = dataset[name].astype(str)
        encoded = {name: netcdf_name(str(name)) for name in dataset.variables}
        for name, written in encoded.items():
            if written != name:
                dataset[name].attrs["long_name"] = name
        return dataset.rename({n: w for n, w in encoded.items() if w != n})


def netcdf_engine() -> str:
    """xarray's engine for .nc files: scipy's netCDF3 writer (the ensemble extra's: faster and
    smaller files than h5netcdf's, benchmarks/netcdf_backends.py), else netCDF4's or h5netcdf's
    where one of them is installed instead."""
    for engine, modules in NETCDF_ENGINES:
        if all(importlib.util.find_spec(m) is not None for m in modules):
            return engine
    raise MissingDependencyError(f"writing .nc files needs scipy (or h5netcdf): "
                                 f"{install_hint('scipy')}", name="scipy")


def _at_least_one_event(time: np.ndarray, micro: np.ndarray, source: np.ndarray
                        ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """member x event arrays with one event column at least, empty (NaN, -1, "") where no
    member had an event: NetCDF readers (scipy's, and xarray through it) cannot reopen a
    variable of an empty dimension, and `dataset.to_netcdf()` is the user's own call."""
    if time.shape[1] > 0:
        return time, micro, source
    members = time.shape[0]
    return (np.full((members, 1), np.nan), np.full((members, 1), -1, dtype=micro.dtype),
            np.full((members, 1), "", dtype=source.dtype))


def _grid(t0: float, tf: float, dt: float) -> np.ndarray:
    """t0 + k*dt up to tf, tf itself last (a point within 1e-9 dt of tf is tf)."""
    steps = int(np.floor((tf - t0) / dt + 1e-9))
    points = t0 + dt * np.arange(steps + 1)
    if tf - points[-1] > 1e-9 * dt:
        points = np.append(points, tf)
    points[-1] = tf
    return points
