"""The engine library exports exactly the functions of its public header, and nothing else
reaches a Python process; the status names Python shows are the engine's."""

from __future__ import annotations

import re
import shutil
import subprocess

import pytest
from syssimx import _paths
from syssimx.engine import status_name


def _declared_functions() -> set[str]:
    header = _paths.engine_header().read_text()
    code = re.sub(r"/\*.*?\*/", "", header, flags=re.DOTALL)
    return set(re.findall(r"\b(ssx_\w+)\s*\(", code))


@pytest.mark.skipif(shutil.which("nm") is None, reason="nm (binutils) is not installed")
def test_engine_exports_only_the_functions_of_its_header() -> None:
    listing = subprocess.run(
        ["nm", "-D", "--defined-only", str(_paths.engine_library())],
        check=True, capture_output=True, text=True,
    ).stdout
    exported = {line.split()[-1] for line in listing.splitlines() if line.strip()}
    assert all(name.startswith("ssx_") for name in exported), sorted(
        name for name in exported if not name.startswith("ssx_"))
    assert exported == _declared_functions()
    # internals of the binding and of the system are not part of the interface
    assert not exported & {"ssx_fmu_generation", "ssx_fmu_values_epoch", "ssx_fmu_remote",
                           "ssx_component_count", "fail_fmi", "history_append",
                           "ssx_fmi3_prepare", "ssx_fmu_step_outcome",
                           "ssx_fmu_enter_event_mode", "ssx_fmu_new_discrete_states"}
    # one loader for every FMI version; FMI 3.0 adds its String and Binary values
    assert {"ssx_fmu_load", "ssx_fmu_get_string", "ssx_fmu_set_string",
            "ssx_fmu_get_binary", "ssx_fmu_set_binary"} <= exported


def test_status_names_come_from_the_engine() -> None:
    assert [status_name(s) for s in range(-1, 6)] == [
        "failed", "OK", "Warning", "Discard", "Error", "Fatal", "Pending"]
    assert status_name(9) == "9"
