"""Every bundled FMU is valid for fmpy, runs in fmpy.simulate_fmu, and is a self-contained
binary: only fmi2 functions exported, only libc and libm needed."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import fmpy
import pytest
from fixture_fmus import FIXTURES, fmu_path
from fmpy import read_model_description
from fmpy.validation import validate_fmu
from syssimx import fmus

# the one list of the bundled FMUs: the stems of models/meson.build's fmu_builds
FMU_BUILDS = re.search(r"^fmu_builds = \[\n(.*?)^\]", (
    Path(__file__).resolve().parents[2] / "models" / "meson.build").read_text(), re.M | re.S)
BUILT = re.findall(r"^\s*\['(\w+)',", FMU_BUILDS.group(1), re.M) if FMU_BUILDS else []
SHIPPED = BUILT
BUILT = [*SHIPPED, *FIXTURES]  # the toolchain builds the test fixtures the same way

# fmi2Functions.h declares 44 functions; an FMU exports all of them and nothing else
FMI2_FUNCTION_COUNT = 44


def test_every_contracted_fmu_is_built_and_no_test_fixture_is_bundled() -> None:
    assert SHIPPED, "no fmu_builds list found in models/meson.build"
    assert set(SHIPPED) <= set(fmus.available())
    assert FIXTURES and all(fmu_path(name) for name in FIXTURES)  # built for tests
    bundled = set(fmus.available())
    assert not bundled & {*FIXTURES, *(f"{name}_fmi3" for name in FIXTURES)}
    with pytest.raises(FileNotFoundError, match="no bundled FMU named 'failing'"):
        fmus.path("failing")


@pytest.mark.parametrize("name", BUILT)
def test_fmpy_finds_no_problem(name: str) -> None:
    assert validate_fmu(fmu_path(name)) == []


@pytest.mark.parametrize("name", [n for n in BUILT if n != "failing"])
def test_simulate_fmu_runs_to_the_stop_time(name: str) -> None:
    result = fmpy.simulate_fmu(fmu_path(name), stop_time=1.0, output_interval=0.01)
    assert result["time"][-1] == pytest.approx(1.0, abs=1e-12)
    assert len(result) == 101


def test_failing_fmu_stops_simulate_fmu() -> None:
    with pytest.raises(Exception, match="fmi2DoStep"):
        fmpy.simulate_fmu(
            fmu_path("failing"),
            stop_time=1.0,
            output_interval=0.1,
            start_values={"fail_time": 0.5},
        )


def _binary(name: str, tmp_path) -> str:
    unzipped = fmpy.extract(fmu_path(name), unzipdir=tmp_path / name)
    return f"{unzipped}/binaries/linux64/{name}.so"


@pytest.mark.parametrize("name", ["pendulum_euler", "pendulum_cvode", "bouncing_ball_cvode"])
def test_binary_exports_only_fmi2_and_needs_only_libc_and_libm(name: str, tmp_path) -> None:
    binary = _binary(name, tmp_path)
    symbols = subprocess.run(
        ["nm", "-D", "--defined-only", binary], check=True, capture_output=True, text=True
    ).stdout.split()
    exported = [s for s in symbols if len(s) > 1 and s[0].isalpha() and not s.isupper()]
    assert len(exported) == FMI2_FUNCTION_COUNT
    assert all(s.startswith("fmi2") for s in exported)
    dynamic = subprocess.run(
        ["readelf", "-d", binary], check=True, capture_output=True, text=True
    ).stdout
    needed = {line.split("[")[1].rstrip("]") for line in dynamic.splitlines() if "(NEEDED)" in line}
    assert needed <= {"libc.so.6", "libm.so.6"}


def test_pendulum_model_structure_declares_the_feedthrough() -> None:
    description = read_model_description(fmu_path("pendulum_cvode"))
    outputs = {u.variable.name: [d.name for d in u.dependencies] for u in description.outputs}
    assert outputs["alpha"] == ["theta", "torque"]
    assert outputs["theta"] == ["theta"]
    units = {u.name: u.baseUnit for u in description.unitDefinitions}
    torque = units["N.m"]
    assert (torque.kg, torque.m, torque.s) == (1, 2, -2)
    assert description.coSimulation.canGetAndSetFMUstate
    assert description.coSimulation.canSerializeFMUstate
