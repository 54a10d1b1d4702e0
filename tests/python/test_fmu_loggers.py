"""FMUs that misuse their logger, as exported FMUs do (issue 33 item 1, issue 34 item 13): a
logger call naming an environment that is not the one the FMU was given (FMI 2.0's 1 and 2,
FMI 3.0's 1) or a component not its own (FMI 1.0), and formats with conversions but no
arguments. Before, each killed the Python process; now the run completes and the message is
kept as the FMU's last message, attributed to "an FMU" where its environment is unknown.
Also an empty FMI 3.0 instantiationToken (issue 33 item 8), read with a warning.

The FMUs are built by meson beside the tests, never installed: tests/c/hostile (FMI 2.0, mode
7), tests/fmus/fmi3_arrays built with FMI3_FOREIGN_ENVIRONMENT and tests/fmus/fmi1_logger."""

from __future__ import annotations

import logging
import re
import zipfile
from pathlib import Path

import pytest
from syssimx import FMUComponent, System
from syssimx._paths import build_dir
from syssimx.engine import lib, string

ROOT = Path(__file__).resolve().parents[2]
FOREIGN_ENVIRONMENT = 7  # the hostile FMU's mode


def built_fmu(*parts: str) -> str:
    path = (build_dir() or ROOT / "build" / "release").joinpath(*parts)
    if not path.is_file():
        pytest.skip(f"the test FMU is not built ({path} is missing): run meson compile")
    return str(path)


def last_message(component: FMUComponent) -> str:
    return string(lib().ssx_fmu_last_message(component.instance.fmu))


def run_alone(component: FMUComponent, stop: float) -> None:
    system = System("logging")
    system.add_component(component)
    system.initialize(0.0)
    system.run(0.0, stop, 0.1)


@pytest.mark.parametrize("isolated", [False, True])
def test_fmi2_messages_naming_environments_1_and_2_are_kept_as_an_fmus(isolated: bool) -> None:
    component = FMUComponent("H", built_fmu("tests", "c", "hostile", "hostile.fmu"),
                             isolated=isolated)
    component.set_parameters(mode=FOREIGN_ENVIRONMENT, fail_time=0.45)
    run_alone(component, 1.0)
    assert component.instance.getReal([0]) == [pytest.approx(1.0)]
    assert last_message(component) == "an FMU: naming environment 2 at t=0.9"
    component.free()


def test_fmi3_message_naming_a_foreign_instance_environment_is_kept_as_an_fmus() -> None:
    component = FMUComponent(
        "A", built_fmu("tests", "fmus", "fmi3_arrays", "fmi3_foreign_environment.fmu"))
    run_alone(component, 1.0)
    assert last_message(component) == "an FMU: stepped naming environment 1"


def test_an_empty_fmi3_instantiation_token_is_warned_about_and_the_fmu_runs(
        tmp_path: Path, caplog: pytest.LogCaptureFixture) -> None:
    """As FMPy 0.3.32's FMI 3.0 containers are written. Before: refused on reading."""
    source = built_fmu("tests", "fmus", "fmi3_arrays", "fmi3_foreign_environment.fmu")
    emptied = tmp_path / "empty_token.fmu"
    with zipfile.ZipFile(source) as original, zipfile.ZipFile(emptied, "w") as copy:
        for item in original.infolist():
            data = original.read(item.filename)
            if item.filename == "modelDescription.xml":
                data = re.sub(rb'instantiationToken="[^"]*"', b'instantiationToken=""', data)
            copy.writestr(item, data)
    with caplog.at_level(logging.WARNING, logger="syssimx.fmu"):
        component = FMUComponent("A", str(emptied))
    assert caplog.messages == [f"{emptied}: the FMI 3.0 description's instantiationToken is "
                               "empty; the FMU is instantiated with the empty token"]
    run_alone(component, 1.0)
    assert component.instance.getReal([0]) == [pytest.approx(1.0)]  # the time


@pytest.mark.parametrize("isolated", [False, True])
def test_fmi1_formats_without_arguments_and_a_foreign_component_are_logged(isolated: bool) -> None:
    """The FMU's format has a number conversion, fifteen string conversions and a floating one,
    and no arguments; it fills the stack with an address no string lies at, so a string
    conversion read through always faulted. A missing number reads as a meaningless one.
    Isolated, the host formats the message and the engine keeps it as the FMU's."""
    component = FMUComponent("L", built_fmu("tests", "fmus", "fmi1_logger", "fmi1_logger.fmu"),
                             isolated=isolated)
    system = System("logging")
    system.add_component(component)
    system.initialize(0.0)
    # logged by fmiInstantiateSlave, naming no component
    assert re.fullmatch(r"instantiated at -?\d+ (%s){15} and \S+", last_message(component))
    system.run(0.0, 1.0, 0.1)
    # FMI 1.0's logger names the FMU's component, not an environment of ours: the message is
    # the FMU's being called, whichever component it names
    assert re.fullmatch(r"stepped at -?\d+ (%s){15} and \S+", last_message(component))
    assert component.instance.getReal([0]) == [pytest.approx(1.0)]
