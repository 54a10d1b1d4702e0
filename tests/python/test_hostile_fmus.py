"""FMUs that misbehave while they run (issue 20's second round): what they hand back is checked
before anyone reads it, and a run stops with an error naming the component and the time.

The FMI 3.0 FMU is tests/fmus/fmi3_arrays built with FMI3_MISBEHAVES: its Binary output `blob`
comes back as NULL with a size of 4096 bytes, and from t = 0.45 on fmi3DoStep returns early at
a lastSuccessfulTime one step past the step's end."""

from __future__ import annotations

from pathlib import Path

import pytest
from syssimx import FMUComponent, System
from syssimx._paths import build_dir
from syssimx.errors import FMUError, SimulationError

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def misbehaving_fmu() -> str:
    build = build_dir() or ROOT / "build" / "release"
    path = build / "tests" / "fmus" / "fmi3_arrays" / "fmi3_misbehaving.fmu"
    if not path.is_file():
        pytest.skip(f"the misbehaving FMI 3.0 test FMU is not built ({path} is missing): run "
                    "meson compile")
    return str(path)


def test_binary_data_null_with_a_size_is_an_fmu_error_naming_the_variable(misbehaving_fmu: str):
    """Before: get_state() returned 4096 bytes of process memory as the value of blob."""
    component = FMUComponent("A", misbehaving_fmu)
    system = System("s")
    system.add_component(component)
    system.initialize(0.0)
    with pytest.raises(FMUError) as caught:
        component.get_state()
    message = str(caught.value)
    assert message.startswith("A: fmi3GetBinary returned Error")
    assert "no data (NULL) with a size of 4096 bytes" in message
    assert message.endswith("(variable 'blob')")


def test_an_early_return_past_the_step_end_stops_the_run(misbehaving_fmu: str):
    """Before: accepted; the outputs were read at the step's end as if the FMU had got
    there."""
    component = FMUComponent("A", misbehaving_fmu)
    system = System("s")
    system.add_component(component)
    system.initialize(0.0)
    with pytest.raises(SimulationError) as caught:
        system.run(0.0, 1.0, 0.1)
    message = str(caught.value)
    assert "component 'A': fmi3DoStep from t=0.5" in message
    assert "returned early at lastSuccessfulTime=0.7" in message
    assert "outside the step's end t=0.6" in message
    times, _ = system.get_history()["A"]
    assert times[-1] == pytest.approx(0.5)  # the samples before the failure are kept
