"""Fallbacks per FMU (issue 35, item 3): an FMU that refuses the input derivative order it is
given runs on at the next lower one (2 -> 1 -> 0), one whose output derivatives are NaN has
its outputs' slopes estimated from the communication points; each is warned of once per FMU
and counted in the statistics, and the run goes on.

The FMU is tests/fmus/derivative_limits: y' = u with u interpolated by the input derivatives
it is given; its parameter max_input_order is the highest order it takes (fmi2Error above),
nan_output_derivatives = 1 makes fmi2GetRealOutputDerivatives tell NaN. Driven by a first one
whose u = 1 (y = t), the second one's y is t^2 / 2."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest
from syssimx import Connection, FMUComponent, GaussSeidelAlgorithm, JacobiAlgorithm, System
from syssimx._paths import build_dir
from syssimx.errors import SysSimXWarning

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def limited_fmu() -> str:
    build = build_dir() or ROOT / "build" / "release"
    path = build / "tests" / "fmus" / "derivative_limits" / "derivative_limits.fmu"
    if not path.is_file():
        pytest.skip(f"the derivative_limits test FMU is not built ({path} is missing): run "
                    "meson compile")
    return str(path)


def ramp_and_integrator(path: str, input_order: int, jacobi: bool = False,
                        **integrator: int) -> System:
    system = System("ramp and integrator")
    system.add_component(FMUComponent("Ramp", path))
    second = FMUComponent("Integrator", path)
    second.set_parameters(**integrator)
    system.add_component(second)
    system.add_connection(Connection("Ramp", "y", "Integrator", "u"))
    algorithm = JacobiAlgorithm if jacobi else GaussSeidelAlgorithm
    system.set_algorithm(algorithm(input_order=input_order))
    return system


def run_warned(system: System) -> tuple[float, list[str], object]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        system.initialize(0.0)
        result = system.run(0.0, 1.0, 0.1)
    messages = [str(w.message) for w in caught if issubclass(w.category, SysSimXWarning)]
    y = float(system.get_history()["Integrator"][1]["y"][-1])
    return y, messages, result.statistics


@pytest.mark.parametrize(("accepted", "jacobi"), [(1, False), (0, False), (1, True)])
def test_a_refused_input_order_falls_back_once(limited_fmu: str, accepted: int, jacobi: bool):
    """Before: fmi2SetRealInputDerivatives' fmi2Error ended the run at t = 0."""
    system = ramp_and_integrator(limited_fmu, 2, jacobi, max_input_order=accepted)
    y, messages, statistics = run_warned(system)
    about = [m for m in messages if "Integrator" in m and "input derivative" in m]
    assert len(about) == 1, messages
    assert f"order {accepted}" in about[0]
    assert statistics.input_order_fallbacks == 1
    assert statistics.output_derivative_fallbacks == 0
    if accepted == 1:
        # u = t moves linearly: first derivatives integrate it exactly (Gauss-Seidel and
        # Jacobi alike, the ramp tells its slope)
        assert y == pytest.approx(0.5, abs=1e-12)
    else:
        # u held over each step at its start: the left Riemann sum of t over 0.1 steps
        assert y == pytest.approx(0.45, abs=1e-12)


def test_an_accepted_input_order_is_no_fallback(limited_fmu: str):
    y, messages, statistics = run_warned(ramp_and_integrator(limited_fmu, 2))
    assert not messages
    assert statistics.input_order_fallbacks == 0
    assert y == pytest.approx(0.5, abs=1e-12)


@pytest.mark.parametrize("input_order", [1, 2])
def test_nan_output_derivatives_fall_back_to_the_communication_points(limited_fmu: str,
                                                                      input_order: int):
    """Before: the NaN slope was handed on to the integrator, which refused it at t = 0."""
    system = ramp_and_integrator(limited_fmu, input_order, jacobi=True)
    system.components["Ramp"].set_parameters(nan_output_derivatives=1)
    y, messages, statistics = run_warned(system)
    about = [m for m in messages if "Ramp" in m and "output derivatives" in m]
    assert len(about) == 1, messages
    assert statistics.output_derivative_fallbacks == 1
    assert statistics.input_order_fallbacks == 0
    # the slope from the last two points is the ramp's 1 from the second step on; the first
    # step has no earlier point, so u is held there (0.1 * 0.1 / 2 short)
    assert y == pytest.approx(0.5 - 0.005, abs=1e-12)
