"""The FMI 3.0 Reference FMUs with a Model Exchange interface (all but Clocks) run as Model
Exchange: the engine integrates them with CVODE through the same component as FMI 2.0 Model
Exchange FMUs, the calls made in FMI 3.0 (fmi3InstantiateModelExchange,
fmi3GetContinuousStateDerivatives, fmi3UpdateDiscreteStates, ...). Compared as
test_model_exchange_reference.py compares the FMI 2.0 builds, with RTOL = 1e-8 given to both
syssimx and FMPy's simulate_fmu(fmi_type="ModelExchange", solver="CVode"):

- BouncingBall, Dahlquist, VanDerPol: on FMPy's grid, the states within 10 * RTOL of the
  accurate solution (BouncingBall up to its third bounce) and no farther from it than FMPy's.
- Roberts (stiff; its two event indicators cross once, at 0.264 s), 0 to 3 s: within 10 * RTOL
  of scipy's Radau at 1e-13, on each state's scale (its largest magnitude, at least its
  nominal: y1 1e-4, y2 1e-2). FMPy's y1 is not (1.02e-7), so "as close as FMPy" is not asked.
- Stair and Feedthrough (no states): FMPy's numbers exactly; Stair's time events at each second
  and its request to terminate at 9 s, without rollback, and its `_out.csv` (1e-12).
- BouncingBall's bounces at the closed-form times within 1e-8, with no rollback; beside an
  indicator of the master located by rollback (fmi3GetFMUState/SetFMUState in Model Exchange's
  modes), each bounce recorded once.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from scipy.integrate import solve_ivp
from syssimx import FMUComponent, SimulationResult, System
from syssimx.errors import SimulationError
from test_fmi3_import import edited
from test_fmi3_reference import fmu, outputs
from test_model_exchange_reference import (
    RTOL,
    assert_external_indicator_located_and_own_events_recorded_once,
    assert_states_within_ten_tolerances_and_as_close_as_fmpy,
    bounce_times,
    grid,
)
from test_reference_fmus import reference_result


def run_me(model: str, t0: float, tf: float, dt: float, tolerance: float = RTOL,
           path: str | None = None) -> tuple[dict[str, np.ndarray], SimulationResult]:
    system = System(model)
    component = FMUComponent("M", path or fmu(model), interface="model-exchange",
                             tolerance=tolerance)
    system.add_component(component)
    system.initialize(t0)
    result = system.run(t0, tf, dt)
    t, values = result["M"]
    return {"time": t.copy(), **{n: v.copy() for n, v in values.items()}}, result


def fmpy_me(model: str, t0: float, tf: float, dt: float) -> np.ndarray:
    return simulate_fmu(fmu(model), fmi_type="ModelExchange", solver="CVode",
                        relative_tolerance=RTOL, start_time=t0, stop_time=tf,
                        output_interval=dt, record_events=False, output=outputs(model))


def robertson(t: np.ndarray) -> dict[str, np.ndarray]:
    """Robertson's kinetics as an ODE in y1, y2 (y3 = 1 - y1 - y2), solved by Radau at 1e-13."""
    def rates(_: float, y: np.ndarray) -> list[float]:
        y3 = 1.0 - y[0] - y[1]
        return [-0.04 * y[0] + 1e4 * y[1] * y3, 0.04 * y[0] - 1e4 * y[1] * y3 - 3e7 * y[1] ** 2]
    solution = solve_ivp(rates, (t[0], t[-1]), [1.0, 0.0], method="Radau", rtol=1e-13,
                         atol=1e-16, t_eval=t)
    return {"y1": solution.y[0], "y2": solution.y[1]}


def test_the_reference_fmus_with_model_exchange_are_the_ones_tested():
    described = {path.stem for path in Path(fmu("Clocks")).parent.glob("*.fmu")
                 if read_model_description(str(path), validate=False).modelExchange}
    assert described == {"BouncingBall", "Dahlquist", "Feedthrough", "Roberts", "Stair",
                         "VanDerPol"}


@pytest.mark.parametrize("model", ["BouncingBall", "Dahlquist", "VanDerPol"])
def test_states_within_ten_tolerances_and_as_close_as_fmpy(model: str):
    result = assert_states_within_ten_tolerances_and_as_close_as_fmpy(model, run_me, fmpy_me)
    assert result.statistics.state_restores == 0


def test_roberts_within_ten_tolerances_of_an_accurate_solution():
    t0, tf, dt = 0.0, 3.0, 0.01
    ours, result = run_me("Roberts", t0, tf, dt)
    theirs = fmpy_me("Roberts", t0, tf, dt)
    np.testing.assert_array_equal(ours["time"], theirs["time"])
    nominal = {"y1": 1e-4, "y2": 1e-2}
    for name, solution in robertson(ours["time"]).items():
        scale = max(float(np.max(np.abs(solution))), nominal[name])
        assert np.max(np.abs(ours[name] - solution)) / scale <= 10 * RTOL, name
    np.testing.assert_allclose(ours["y3"], 1.0 - ours["y1"] - ours["y2"], rtol=0, atol=1e-15)
    assert [(round(e.t, 3), e.event) for e in result.events] == [(0.264, "state_event")]


@pytest.mark.parametrize("model", ["Stair", "Feedthrough"])
def test_models_without_states_equal_fmpy(model: str):
    t0, tf, dt = grid(model)
    ours, result = run_me(model, t0, tf, dt)
    theirs = fmpy_me(model, t0, tf, dt)
    # Stair asks to terminate at its event at 9 s: FMPy stops before sampling 9 s, the engine
    # ends the run after the step that reached it (as the reference's simulator does)
    n = len(theirs)
    for name in outputs(model):
        np.testing.assert_array_equal(ours[name][:n], theirs[name], err_msg=name)
    if model == "Stair":
        np.testing.assert_allclose(ours["counter"], reference_result(model)["counter"],
                                   rtol=1e-12, atol=0)
        assert [(e.t, e.event) for e in result.events] == [
            (float(k), "time_event") for k in range(1, 10)]
        assert (result.termination.component, result.termination.time) == ("M", 9.0)
        assert result.statistics.state_restores == 0


def test_bouncing_ball_bounces_at_the_closed_form_times_without_rollback():
    """Its event indicator h is a CVODE root function: each bounce is found inside the step
    at its time, handled with fmi3EnterEventMode and fmi3UpdateDiscreteStates, and recorded at
    (t, 0), with no rollback."""
    _, result = run_me("BouncingBall", 0.0, 3.0, 0.01, tolerance=1e-12)
    events = result.events
    expected = bounce_times()
    assert len(events) == len(expected) == 11
    assert np.max(np.abs(np.array([e.t for e in events]) - expected)) < 1e-8
    assert {(e.component, e.event, e.micro, e.own) for e in events} == {
        ("M", "state_event", 0, True)}
    statistics = result.statistics
    assert (statistics.own_events, statistics.state_restores, statistics.events) == (11, 0, 0)
    assert statistics.do_step_calls == 300


def test_external_indicator_is_located_by_rollback_and_own_events_recorded_once():
    assert_external_indicator_located_and_own_events_recorded_once(fmu("BouncingBall"))


def test_auto_takes_co_simulation_and_model_exchange_when_it_is_the_only_interface(
        tmp_path: Path):
    assert FMUComponent("Ball", fmu("BouncingBall")).fmu_interface.name == "co-simulation"
    only = edited(tmp_path, fmu("BouncingBall"), ("<CoSimulation", "<!--CoSimulation"),
                  ('hasEventMode="true"/>', 'hasEventMode="true"-->'))
    ball = FMUComponent("Ball", only)
    assert ball.fmu_interface.name == "model-exchange" and ball.model_exchange
    _, result = run_me("BouncingBall", 0.0, 1.0, 0.01, tolerance=1e-12, path=only)
    assert abs(result.events[0].t - bounce_times()[0]) < 1e-8


def test_an_instance_counting_other_event_indicators_than_its_description_is_refused(
        tmp_path: Path):
    """FMI 3.0 asks the instance: a description whose ModelStructure lists no EventIndicator
    while the binary has one fails with both counts named."""
    path = edited(tmp_path, fmu("BouncingBall"), ('<EventIndicator valueReference="1"/>', ""))
    with pytest.raises(SimulationError) as info:
        run_me("BouncingBall", 0.0, 1.0, 0.01, path=path)
    assert str(info.value) == ("component 'M': event indicators: the instance has 1 "
                               "(fmi3GetNumberOfEventIndicators at t=0), its modelDescription "
                               "declares 0")
