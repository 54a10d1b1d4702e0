"""Port names in output files (issue 34, items 4 and 5): a streamed CSV header is quoted as the
csv module quotes, so "a[1,2]" stays one column; a NetCDF name with '/', a line break or
beyond ASCII is written encoded with the name itself as long_name, readable alike by scipy and
xarray; an ensemble's Dataset round-trips through to_netcdf also when no member had events."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest
from syssimx import System, TableSource
from syssimx.ensemble.member import MemberResult
from syssimx.ensemble.result import EnsembleResult

NAMES = ["a[1,2]", "x/y", "line\nbreak", "θ", 'say "hi"']


def table_system() -> System:
    """A table source whose outputs bear the names above (0, 1, 2, ... times 1, 2 over t)."""
    fields = [("time", np.float64), *((name, np.float64) for name in NAMES)]
    table = np.zeros(2, dtype=fields)
    table["time"] = [0.0, 1.0]
    for k, name in enumerate(NAMES):
        table[name] = [float(k), 2.0 * k]
    system = System("named")
    system.add_component(TableSource("T", table))
    system.initialize(0.0)
    return system


def test_a_streamed_csv_header_is_quoted(tmp_path: Path):
    """Before: the header was joined with commas, a[1,2] became two columns."""
    path = tmp_path / "run.csv"
    table_system().run(0.0, 1.0, 0.5, stream_to=path)
    with path.open(newline="") as stream:
        rows = list(csv.reader(stream))
    assert rows[0] == ["time", "micro", *(f"T.{name}" for name in NAMES)]
    assert all(len(row) == len(rows[0]) for row in rows)
    assert [float(cell) for cell in rows[-1][2:]] == [2.0 * k for k in range(len(NAMES))]


def test_streamed_netcdf_names_read_alike_in_scipy_and_xarray(tmp_path: Path):
    """Before: the names were written as they are, '/' and line breaks that NetCDF forbids,
    and scipy read "T.θ" back garbled (its UTF-8 bytes taken as Latin-1)."""
    scipy_io = pytest.importorskip("scipy.io")
    xr = pytest.importorskip("xarray")
    path = tmp_path / "run.nc"
    table_system().run(0.0, 1.0, 0.5, stream_to=path)
    expected = {f"T.{name}": 2.0 * k for k, name in enumerate(NAMES)}
    with scipy_io.netcdf_file(path, "r", mmap=False) as file:
        last = {(variable.long_name.decode() if hasattr(variable, "long_name") else name):
                float(variable[-1]) for name, variable in file.variables.items()
                if name not in ("time", "micro")}
        assert all(name.isascii() and "/" not in name and name.isprintable()
                   for name in file.variables)
    assert last == expected
    with xr.open_dataset(path) as dataset:
        assert {dataset[name].attrs.get("long_name", name): float(dataset[name][-1])
                for name in dataset.data_vars if name not in ("time", "micro")} == expected


def no_event_members() -> list[MemberResult]:
    return [MemberResult(k, {"P.k": float(k)}, "ok", time=np.array([0.0, 1.0]),
                         micro=np.array([0, 0]), outputs={"P.x": np.array([k, 2.0 * k])})
            for k in range(2)]


@pytest.mark.parametrize("engine", ["scipy", "xarray"])
def test_an_ensemble_dataset_without_events_round_trips_through_netcdf(tmp_path: Path,
                                                                       engine: str):
    """Before: dataset.to_netcdf() wrote an empty `event` dimension that neither scipy nor
    xarray could open again."""
    xr = pytest.importorskip("xarray")
    scipy_io = pytest.importorskip("scipy.io")
    result = EnsembleResult(no_event_members(), ["P.k"], 0.0, 1.0, 1.0, 0.0)
    path = tmp_path / "ensemble.nc"
    result.dataset.to_netcdf(path)
    if engine == "scipy":
        with scipy_io.netcdf_file(path, "r", mmap=False) as file:
            assert file.variables["P.x"][:].tolist() == [[0.0, 0.0], [1.0, 2.0]]
            assert np.isnan(file.variables["event_time"][:]).all()
        return
    with xr.open_dataset(path) as dataset:
        np.testing.assert_array_equal(dataset["P.x"].values, result.dataset["P.x"].values)
        assert dataset.sizes["event"] == 1 and np.isnan(dataset["event_time"].values).all()
        assert list(dataset["status"].values) == ["ok", "ok"]


def test_an_ensemble_written_to_netcdf_keeps_names_beyond_ascii(tmp_path: Path):
    """Before: scipy's writer failed on "P.θ" (it writes names as Latin-1)."""
    xr = pytest.importorskip("xarray")
    members = no_event_members()
    for member in members:
        member.outputs["P.θ/2"] = member.outputs["P.x"] / 2
    path = EnsembleResult(members, ["P.k"], 0.0, 1.0, 1.0, 0.0).write(tmp_path / "e.nc")
    with xr.open_dataset(path) as dataset:
        named = {dataset[name].attrs.get("long_name", name): name for name in dataset.data_vars}
        assert dataset[named["P.θ/2"]].values.tolist() == [[0.0, 0.0], [0.5, 1.0]]
