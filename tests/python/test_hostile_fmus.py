"""FMUs that misbehave while they run (issue 20's second round): what they hand back is checked
before anyone reads it, and a run stops with an error naming the component and the time.

The FMI 3.0 FMU is tests/fmus/fmi3_arrays built with FMI3_MISBEHAVES: its Binary output `blob`
comes back as NULL with a size of 4096 bytes at t = 0.3, and from t = 0.45 on fmi3DoStep returns
early at a lastSuccessfulTime one step past the step's end."""

from __future__ import annotations

import math
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
    """Before: get_state() returned 4096 bytes of process memory as the value of blob. blob is
    an output port, read after every step: the run stops at t = 0.3, and get_state() there
    names the variable."""
    component = FMUComponent("A", misbehaving_fmu)
    system = System("s")
    system.add_component(component)
    system.initialize(0.0)
    with pytest.raises(SimulationError) as stopped:
        system.run(0.0, 0.4, 0.1)
    assert str(stopped.value).startswith("component 'A': fmi3GetBinary failed at t=0.3")
    assert "no data (NULL) with a size of 4096 bytes" in str(stopped.value)
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
    system.initialize(0.4)
    with pytest.raises(SimulationError) as caught:
        system.run(0.4, 1.0, 0.1)
    message = str(caught.value)
    assert "component 'A': fmi3DoStep from t=0.5" in message
    assert "returned early at lastSuccessfulTime=0.7" in message
    assert "outside the step's end t=0.6" in message
    times, _ = system.get_history()["A"]
    assert times[-1] == pytest.approx(0.5)  # the samples before the failure are kept


@pytest.fixture(scope="module")
def nan_indicator_fmu() -> str:
    build = build_dir() or ROOT / "build" / "release"
    path = build / "tests" / "fmus" / "nan_indicator" / "nan_indicator.fmu"
    if not path.is_file():
        pytest.skip(f"the NaN indicator test FMU is not built ({path} is missing)")
    return str(path)


def decay(path: str, poison: float, allow_non_finite: bool | None = None) -> System:
    component = FMUComponent("D", path, interface="model-exchange")
    component.set_parameters(poison=poison)
    system = System("decay")
    system.add_component(component)
    system.initialize(0.0, tolerance=1e-10, allow_non_finite=allow_non_finite)
    return system


def test_the_model_exchange_indicator_crosses_at_ln_2(nan_indicator_fmu: str):
    """The reference the NaN case is judged against: x' = -x, x - 1/2 falls through 0 at
    t = ln 2 (CVODE at a relative tolerance of 1e-10: the crossing to about 1e-9)."""
    result = decay(nan_indicator_fmu, 0.0).run(0.0, 1.0, 0.1)
    times = sorted({event.t for event in result.events})
    assert times == [pytest.approx(math.log(2), abs=1e-8)]


def test_a_nan_event_indicator_stops_the_run_naming_it(nan_indicator_fmu: str):
    """Before: the run ended with no event at all (a NaN never changes sign)."""
    system = decay(nan_indicator_fmu, 1.0)
    with pytest.raises(SimulationError) as caught:
        system.run(0.0, 1.0, 0.1)
    assert str(caught.value).startswith("component 'D': event indicator 0 (of 1) is nan at t=0")
    assert "non-finite values stop the run unless they are allowed" in str(caught.value)


def test_a_nan_event_indicator_is_ignored_when_non_finite_values_are_allowed(
        nan_indicator_fmu: str):
    result = decay(nan_indicator_fmu, 1.0, allow_non_finite=True).run(0.0, 1.0, 0.1)
    t, values = result["D"]
    assert t[-1] == 1.0 and values["x"][-1] == pytest.approx(math.exp(-1.0), rel=1e-8)
