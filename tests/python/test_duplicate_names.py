"""FMUs that name two variables alike (the OSP dp-ship demo's FMI 1.0 DPController declares
iex, iey and iepsi twice; FMPy and libcosim run it): the FMU is read with one warning naming
the file and the names, runs, and only addressing an ambiguous name is an error listing the
value references. The FMUs are the bundled ones with locals of the same names appended."""

from __future__ import annotations

import logging
import zipfile
from pathlib import Path

import pytest
from syssimx import Connection, FMUComponent, System, fmus
from syssimx.errors import ConfigurationError

# version -> (bundled FMU, the locals appended, a name each repeats with the value references)
CASES = {
    "FMI 1.0": ("pendulum_cvode_fmi1",
                '<ScalarVariable name="theta0" valueReference="20" variability="continuous" '
                'causality="internal"><Real/></ScalarVariable>'
                '<ScalarVariable name="torque" valueReference="21" variability="continuous" '
                'causality="internal"><Real/></ScalarVariable>',
                {"theta0": "7, 20", "torque": "4, 21"}),
    "FMI 2.0": ("gain",
                '<ScalarVariable name="k" valueReference="7" causality="local" '
                'variability="continuous"><Real/></ScalarVariable>',
                {"k": "2, 7"}),
    "FMI 3.0": ("gain_fmi3",
                '<Float64 name="k" valueReference="7" causality="local" '
                'variability="continuous"/>',
                {"k": "2, 7"}),
}


def with_duplicates(tmp_path: Path, version: str) -> Path:
    name, extra, _ = CASES[version]
    source = Path(fmus.path(name))
    path = tmp_path / f"{name}_duplicates.fmu"
    with zipfile.ZipFile(source) as original, zipfile.ZipFile(path, "w") as edited:
        for entry in original.namelist():
            data = original.read(entry)
            if entry == "modelDescription.xml":
                text = data.decode()
                assert text.count("</ModelVariables>") == 1
                data = text.replace("</ModelVariables>", extra + "</ModelVariables>").encode()
            edited.writestr(entry, data)
    return path


@pytest.mark.parametrize("version", sorted(CASES))
def test_one_warning_names_the_file_and_the_names(tmp_path: Path, version: str,
                                                  caplog: pytest.LogCaptureFixture) -> None:
    path = with_duplicates(tmp_path, version)
    with caplog.at_level(logging.WARNING, logger="syssimx.fmu"):
        FMUComponent("A", str(path))
        FMUComponent("B", str(path))
    warned = [r.getMessage() for r in caplog.records if "several variables" in r.getMessage()]
    assert len(warned) == 1, warned
    assert warned[0].startswith(path.name)
    for name, references in CASES[version][2].items():
        assert f"{name!r} (value references {references})" in warned[0]


@pytest.mark.parametrize("version", sorted(CASES))
def test_setting_an_ambiguous_parameter_lists_the_value_references(tmp_path: Path,
                                                                   version: str) -> None:
    component = FMUComponent("F", str(with_duplicates(tmp_path, version)))
    name, references = next(iter(CASES[version][2].items()))
    with pytest.raises(ConfigurationError, match=f"value references {references}: the name "
                                                 "is ambiguous"):
        component.set_parameters(**{name: 2.0})


@pytest.mark.parametrize("version", ["FMI 2.0", "FMI 3.0"])
def test_the_rest_of_the_gain_runs(tmp_path: Path, version: str) -> None:
    """k is left at its start 1 (the FMU's own value): y = u."""
    gain = FMUComponent("G", str(with_duplicates(tmp_path, version)))
    gain.set_inputs({"u": 3.0})
    system = System("s")
    system.add_component(gain)
    system.initialize(0.0)
    _, values = system.run(0.0, 0.1, 0.05)["G"]
    assert list(values["y"]) == [3.0, 3.0, 3.0]


def test_the_fmi1_pendulum_runs_and_refuses_a_connection_to_an_ambiguous_input(
        tmp_path: Path) -> None:
    pendulum = FMUComponent("P", str(with_duplicates(tmp_path, "FMI 1.0")))
    pendulum.set_parameters(omega0=1.0)
    system = System("s")
    system.add_component(pendulum)
    system.add_component(FMUComponent("G", fmus.path("gain")))
    with pytest.raises(ConfigurationError, match="value references 4, 21: the name is "
                                                 "ambiguous"):
        system.add_connection(Connection("G", "y", "P", "torque"))
    system.initialize(0.0)
    _, values = system.run(0.0, 0.1, 0.05)["P"]
    assert values["theta"][0] == 0.0 and values["theta"][-1] > 0.09  # omega0 = 1 rad/s
