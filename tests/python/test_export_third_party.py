"""Systems other tools wrote, exported by `syssimx export` as FMI 2.0 and 3.0 FMUs and run by
FMPy alone (no syssimx importable, a copy in a fresh folder) at the system's own step: libcosim's
quarter truck (third-party FMUs with String parameters, the ecco step control), the SSP and OSP
files of OMSimulator and libcosim that syssimx runs, YAML systems of the Reference FMUs
with declarative handlers, and members with odd and long names. Every output equals syssimx's
own run of the same file at every grid point, to the bit, and `fmpy.validation` finds no
problem."""

from __future__ import annotations

import re
import shutil
import warnings
import zipfile
from html import unescape
from pathlib import Path
from typing import Any
from xml.sax.saxutils import escape

import numpy as np
import pytest
from coupling_samples import coupling_samples_root
from exported_fmus import run_with_fmpy_alone
from fmpy import simulate_fmu
from fmpy.validation import validate_fmu
from reference_root import reference_root
from ssp_samples import available_samples
from syssimx.cli.main import main
from syssimx.system.loader import build_system
from syssimx.system_files import read_system_file

VERSIONS = ["2.0", "3.0"]

# the sample files syssimx runs (test_system_files_samples.py), with the stop time and step the
# comparison uses: the file's own where it has them
SAMPLES = {
    "libcosim/msmi/OspSystemStructure.xml": (0.5, None),
    "libcosim/msmi/OspSystemStructure_Bond.xml": (0.05, None),
    "libcosim/msmi/OspSystemStructure_Dahlquist.xml": (1.0, None),
    "libcosim/msmi/OspSystemStructure_Dahlquist_proxyfmu.xml": (1.0, None),
    "libcosim/msmi/OspSystemStructure_EndTime.xml": (None, None),
    "libcosim/msmi/OspSystemStructure_proxyfmu.xml": (0.05, None),
    "libcosim/ssp/linear_transformation/SystemStructure.ssd": (1.0, 0.1),
    "omsimulator/LinearTransformation/SystemStructure.ssd": (None, 0.1),
    "omsimulator/import_export_parameters1/SystemStructure.ssd": (None, 0.1),
    "omsimulator/toplevelparameter1/SystemStructure.ssd": (None, None),
}


def truck() -> Path:
    path = coupling_samples_root() / "quarter_truck" / "OspSystemStructure.xml"
    if not path.is_file():
        pytest.skip(f"libcosim's quarter truck is absent (no {path})")
    return path


def reference_fmu(relative: str) -> Path:
    path = reference_root() / relative
    if not path.is_file():
        pytest.skip(f"the Reference FMUs are absent (no {path})")
    return path


def exported_outputs(fmu: Path) -> list[str]:
    """The FMU's outputs by name, from its modelDescription."""
    document = zipfile.ZipFile(fmu).read("modelDescription.xml").decode()
    return [unescape(name) for name in
            re.findall(r'name="([^"]+)"[^>]*causality="output"', document)]


def grid_samples(system: Any, name: str, times: np.ndarray) -> np.ndarray:
    """The system's recorded `Component.port` at `times`: the last sample at each (an event
    instant's value after the event)."""
    component = max((c for c in system.components if name.startswith(f"{c}.")), key=len)
    port = name[len(component) + 1:]
    recorded, values = system.components[component].get_history_arrays([port])
    step = float(np.min(np.diff(times)))
    picked = []
    for t in times:
        at = np.flatnonzero(np.abs(recorded - t) <= 1e-9 * step)
        assert at.size, f"{name}: no sample at {t}"
        picked.append(values[port][at[-1]])
    return np.array(picked)


def assert_fmpy_gives_syssimx_s_run(fmu: Path, system: Any, stop: float, step: float,
                                    start: float = 0.0) -> tuple[dict[str, list[float]], Any]:
    """FMPy's run of `fmu` at `step` equals `system` run directly from `start` to `stop` at
    every grid point, bit for bit; the export passes FMPy's validation. FMPy's columns and
    the system's run result."""
    assert validate_fmu(str(fmu)) == []
    outputs = exported_outputs(fmu)
    result = run_with_fmpy_alone(fmu, outputs=outputs, stop_time=stop, interval=step)
    system.initialize(start)
    run = system.run(start, stop, step)
    times = np.array(result["time"])
    assert times[-1] == pytest.approx(stop)
    for name in outputs:
        if name in ("events", "last_event_time"):
            continue
        np.testing.assert_array_equal(result[name], grid_samples(system, name, times),
                                      err_msg=name)
    return result, run


def read_quietly(path: Path) -> Any:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return read_system_file(path)


def export_with_cli(path: Path, fmu: Path, fmi_version: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert main(["export", str(path), "-o", str(fmu), "--fmi-version", fmi_version]) == 0


@pytest.mark.parametrize("fmi_version", VERSIONS)
def test_the_quarter_truck_exports_and_fmpy_runs_it_as_syssimx_does(tmp_path, fmi_version):
    """libcosim's quarter truck: two third-party FMUs (each with the String parameter
    solverType = "Euler" the file sets), the ecco step control at 1e-4 s; 100 steps."""
    path = truck()
    fmu = tmp_path / f"quarter_truck_{fmi_version[0]}.fmu"
    export_with_cli(path, fmu, fmi_version)
    plan = zipfile.ZipFile(fmu).read("resources/system.plan").decode()
    assert plan.count('string 1 "Euler"') == 2
    result, _ = assert_fmpy_gives_syssimx_s_run(fmu, read_quietly(path).system, 0.01, 1e-4)
    assert result["chassis.velocity"][-1] != 0.0  # the truck moved


@pytest.mark.parametrize("fmi_version", VERSIONS)
@pytest.mark.parametrize("name", sorted(SAMPLES))
def test_each_sample_file_exports_and_fmpy_runs_it_as_syssimx_does(tmp_path, name,
                                                                   fmi_version):
    path = available_samples() / name
    fmu = tmp_path / f"sample_{fmi_version[0]}.fmu"
    export_with_cli(path, fmu, fmi_version)
    imported = read_quietly(path)
    stop, step = SAMPLES[name]
    stop = stop if stop is not None else imported.experiment.stop_time
    step = step if step is not None else imported.experiment.step_size
    assert_fmpy_gives_syssimx_s_run(fmu, imported.system, stop, step,
                                    imported.experiment.start_time or 0.0)


def write_description(folder: Path, name: str, text: str) -> Path:
    path = folder / f"{name}.yaml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("fmi_version", VERSIONS)
def test_an_indicator_on_a_reference_fmu_s_output_is_located_inside_the_export(tmp_path,
                                                                                 fmi_version):
    """The FMI 2.0 VanDerPol, an indicator on x0 falling through 0, a Reinitialize handler
    (mu = 0.5): both crossings in 5 s are located inside the FMU at syssimx's own times."""
    vdp = reference_fmu("fmi2/VanDerPol.fmu")
    path = write_description(tmp_path, "vdp", f"""
system: {{name: van der pol restarted}}
components:
  - name: V
    fmu: {vdp}
    event_indicators:
      - {{name: crossing, variable: x0, direction: falling}}
    event_handlers:
      - input: restart
        reinitialize: {{mu: 0.5}}
event_connections:
  - {{src: V.crossing, dst: V.restart}}
algorithm: {{type: hybrid, tol_time: 1.0e-9, tol_value: 1.0e-9}}
""")
    fmu = build_system(path).export_fmu(tmp_path / f"vdp_{fmi_version[0]}.fmu",
                                        fmi_version=fmi_version, step_size=0.01)
    result, run = assert_fmpy_gives_syssimx_s_run(fmu, build_system(path), 5.0, 0.01)
    located = [event.t for event in run.events]
    assert len(located) == 2 and result["events"][-1] == 2
    first = int(np.flatnonzero(np.array(result["events"]) == 1)[0])
    assert result["last_event_time"][first] == located[0]
    assert result["last_event_time"][-1] == located[1]


def ball_restarts_decay(folder: Path) -> Path:
    """The FMI 3.0 BouncingBall whose own events restart the FMI 3.0 Dahlquist (Reinitialize
    k = 2, x from its start 1)."""
    ball = reference_fmu("fmi3/BouncingBall.fmu")
    decay = reference_fmu("fmi3/Dahlquist.fmu")
    return write_description(folder, "ball", f"""
system: {{name: ball restarts decay}}
components:
  - name: B
    fmu: {ball}
  - name: D
    fmu: {decay}
    event_handlers:
      - input: restart
        reinitialize: {{k: 2.0}}
event_connections:
  - {{src: B.own_events, dst: D.restart}}
algorithm: {{type: hybrid, tol_time: 1.0e-9, tol_value: 1.0e-9}}
""")


@pytest.mark.parametrize("fmi_version", VERSIONS)
def test_a_reference_ball_s_own_events_restart_another_member_inside_the_export(tmp_path,
                                                                                  fmi_version):
    """The FMI 3.0 BouncingBall's own events (its bounces, handled in its own steps) restart
    the FMI 3.0 Dahlquist (Reinitialize k = 2, x from its start 1) inside the export; the
    export's events and last_event_time count them."""
    path = ball_restarts_decay(tmp_path)
    fmu = build_system(path).export_fmu(tmp_path / f"ball_{fmi_version[0]}.fmu",
                                        fmi_version=fmi_version, step_size=0.01)
    result, run = assert_fmpy_gives_syssimx_s_run(fmu, build_system(path), 3.0, 0.01)
    # the FMU's own count and time of events take in the members' own events
    assert run.statistics.own_events > 0
    assert result["events"][-1] == run.statistics.own_events
    assert result["last_event_time"][-1] == run.events[-1].t
    decayed = np.array(result["D.x"])
    assert np.any(np.diff(decayed) > 0.5)  # restarted from 1 at a bounce


def test_an_fmi3_export_returns_early_at_a_reference_ball_s_own_events(tmp_path):
    """FMPy allowing early return gets the FMI 3.0 export's doStep back right after each of
    the BouncingBall's own events (0.01 s steps): every time off the grid FMPy samples is one of
    syssimx's own run's event times, and every such time off the grid is sampled."""
    path = ball_restarts_decay(tmp_path)
    fmu = build_system(path).export_fmu(tmp_path / "ball_3.fmu", fmi_version="3.0",
                                        step_size=0.01)
    result = simulate_fmu(str(fmu), stop_time=3.0, output_interval=0.01,
                          early_return_allowed=True, output=["D.x", "events"])
    system = build_system(path)
    system.initialize(0.0)
    own = np.array([event.t for event in system.run(0.0, 3.0, 0.01).events])
    times = np.array(result["time"])

    def off_grid(t: np.ndarray) -> np.ndarray:
        return t[np.abs(t / 0.01 - np.round(t / 0.01)) > 1e-6]

    assert off_grid(own).size > 10
    np.testing.assert_allclose(off_grid(times), off_grid(own), rtol=0, atol=1e-9)
    assert result["events"][-1] == own.size


@pytest.mark.parametrize("fmi_version", VERSIONS)
def test_members_with_odd_and_long_names_export(tmp_path, fmi_version):
    """An OSP file (in a folder whose name has a space, a percent sign and non-ASCII letters)
    whose simulators, two instances of libcosim's Dahlquist FMU, are named with quotes, an
    ampersand, spaces and Greek letters, and with 230 characters."""
    folder = tmp_path / "odd folder %41 ü"
    folder.mkdir()
    shutil.copy(available_samples() / "libcosim" / "fmi2" / "Dahlquist.fmu", folder)
    odd = 'dq "quoted" & spaced ü λ'
    long = "a_member_whose_name_is_long_" * 8 + "end"
    path = folder / "OspSystemStructure.xml"
    path.write_text(f"""<?xml version="1.0" encoding="UTF-8"?>
<OspSystemStructure xmlns="http://opensimulationplatform.com/MSMI/OSPSystemStructure"
                    version="0.1">
  <StartTime>0.0</StartTime>
  <BaseStepSize>0.1</BaseStepSize>
  <Algorithm>fixedStep</Algorithm>
  <Simulators>
    <Simulator name="{escape(odd, {'"': '&quot;'})}" source="Dahlquist.fmu">
      <InitialValues><InitialValue variable="k"><Real value="2"/></InitialValue></InitialValues>
    </Simulator>
    <Simulator name="{long}" source="Dahlquist.fmu"/>
  </Simulators>
</OspSystemStructure>
""", encoding="utf-8")
    fmu = tmp_path / "odd.fmu"
    export_with_cli(path, fmu, fmi_version)
    result, _ = assert_fmpy_gives_syssimx_s_run(fmu, read_quietly(path).system, 1.0, 0.1)
    assert result[f"{odd}.x"][-1] < result[f"{long}.x"][-1]  # k = 2 decays faster than k = 1
