"""FMI 3.0 Model Exchange with a periodic input clock: the engine's integration stops at each
tick, enters event mode, ticks the clock (fmi3SetClock) and updates the discrete states.

The toolchain's sampled_signal_fmi3 (models/SampledSignal) has a continuous state
x' = -x / tau and a clock `sample` (interval 0.1 s) whose ticks set the clocked outputs
y := x and ticks := ticks + 1. The hand-computed reference: x(t) = x0 exp(-t / tau), and at
t in [t_k, t_k + T), t_k = k T, y = x(t_k) and ticks = k + 1."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from fmpy.validation import validate_fmu
from reference_root import reference_root
from syssimx import (
    EventConnection,
    FMUComponent,
    HybridAlgorithm,
    JacobiAlgorithm,
    System,
    fmus,
)
from syssimx.errors import FMUFileError
from syssimx.system import SimulationResult
from test_fmi3_import import edited

SIGNAL = "sampled_signal_fmi3"
PERIOD = 0.1  # the clock's intervalDecimal
TAU = 0.5  # the default time constant
TOLERANCE = 1e-10
FEEDTHROUGH = reference_root() / "fmi3" / "Feedthrough.fmu"

# FMPy 0.3.32 simulate_fmu(fmi_type="ModelExchange", stop_time=1.0, output_interval=0.25,
# relative_tolerance=1e-10, solver="CVode") on sampled_signal_fmi3.fmu: x at 0, 0.25, ..., 1.
# FMPy's Model Exchange loop calls no fmi3SetClock, so there y and ticks stay at their start 0;
# x, which no tick moves, is what both importers integrate.
FMPY_X = (1.0, 0.6065306595072124, 0.3678794413023851, 0.22313016038146835,
          0.13533528347113327)


def signal(name: str = "S", tau: float = TAU) -> FMUComponent:
    component = FMUComponent(name, fmus.path(SIGNAL), interface="model-exchange",
                             tolerance=TOLERANCE)
    component.set_parameters(tau=tau)
    return component


def run(dt: float, tf: float = 1.0, components: tuple[FMUComponent, ...] | None = None,
        threads: int = 1) -> SimulationResult:
    system = System("sampled signal")
    for component in components or (signal(),):
        system.add_component(component)
    system.set_algorithm(JacobiAlgorithm(threads=threads))
    system.initialize(0.0)
    return system.run(0.0, tf, dt)


def last_tick(t: float) -> float:
    """t_k: the last tick at or before t (rounded to the grid's precision)."""
    return math.floor(t / PERIOD + 1e-9) * PERIOD


def test_the_fmu_validates_with_fmpy() -> None:
    assert validate_fmu(fmus.path(SIGNAL)) == []


def test_ticks_inside_steps_sample_x_at_the_tick_as_the_hand_reference() -> None:
    """dt = 0.25: most ticks fall inside steps; the integration stops at each."""
    result = run(0.25)
    t, values = result["S"]
    assert list(np.round(t, 9)) == [0.0, 0.25, 0.5, 0.75, 1.0]
    ticks = [e for e in result.events if e.event == "clock_tick"]
    assert [round(e.t, 12) for e in ticks] == [round(k * PERIOD, 12) for k in range(1, 11)]
    assert all(e.component == "S" for e in ticks)
    sampled = [math.exp(-last_tick(time) / TAU) for time in t]
    np.testing.assert_allclose(values["y"], sampled, rtol=1e-7)
    assert list(values["ticks"]) == [math.floor(time / PERIOD + 1e-9) + 1 for time in t]
    np.testing.assert_allclose(values["x"], np.exp(-t / TAU), rtol=1e-7)


def test_x_equals_fmpy_s() -> None:
    _, values = run(0.25)["S"]
    np.testing.assert_allclose(values["x"], FMPY_X, rtol=1e-7)


def test_clocked_outputs_change_only_at_ticks() -> None:
    """Communication points a sixteenth of a period apart: at each tick, the point just
    before holds the previous sample, the tick and the point just after hold the new one."""
    step = PERIOD / 16
    t, values = run(step, tf=0.5)["S"]
    ticks_seen = 0
    for i in range(1, len(t) - 1):
        k = round(t[i] / PERIOD)
        if abs(t[i] - k * PERIOD) > 1e-9:
            continue
        ticks_seen += 1
        before, at, after = values["y"][i - 1], values["y"][i], values["y"][i + 1]
        assert before == pytest.approx(math.exp(-(k - 1) * PERIOD / TAU), rel=1e-7)
        assert at == after == pytest.approx(math.exp(-k * PERIOD / TAU), rel=1e-7)
        assert (values["ticks"][i - 1], values["ticks"][i], values["ticks"][i + 1]) == (
            k, k + 1, k + 1)
    assert ticks_seen == 4  # 0.1 to 0.4; the tick of 0.5 ends the run
    # between ticks y is constant
    changes = t[1:][np.diff(values["y"]) != 0]
    np.testing.assert_allclose(changes, [PERIOD * k for k in range(1, 6)], atol=1e-12)


def test_two_clocked_fmus_on_two_threads_give_the_same_run() -> None:
    def both(threads: int) -> tuple[list, dict]:
        result = run(0.25, components=(signal("A"), signal("B", tau=0.25)), threads=threads)
        events = [(e.t, e.micro, e.component, e.event) for e in result.events]
        return events, {name: result[name][1]["y"].tolist() for name in ("A", "B")}

    events, samples = both(1)
    assert sum(1 for e in events if e[2] == "B") == 10
    assert samples["B"][-1] == pytest.approx(math.exp(-1.0 / 0.25), rel=1e-7)
    assert both(2) == (events, samples)
    assert both(1) == (events, samples)


@pytest.mark.skipif(not FEEDTHROUGH.is_file(), reason=f"no Reference FMU {FEEDTHROUGH}")
def test_model_exchange_refuses_a_clock_it_cannot_tick_naming_it(tmp_path: Path) -> None:
    """A triggered input clock added to Feedthrough.fmu: Model Exchange has no interval to
    plan its ticks by."""
    clock = ('<Int32 name="Int32_output" valueReference="20" causality="output"',
             '<Clock name="tick" valueReference="9001" causality="input" '
             'intervalVariability="triggered"/>'
             '<Int32 name="Int32_output" valueReference="20" causality="output" '
             'clocks="9001"')
    triggered = edited(tmp_path, str(FEEDTHROUGH), clock)
    with pytest.raises(FMUFileError, match=r"Clock 'tick' \(input, intervalVariability "
                                           r"triggered\)"):
        FMUComponent("F", triggered, interface="model-exchange")



def ticks_and_crossings(threads: int = 1) -> list[tuple[float, int, str, str]]:
    """Two clocked FMUs as Model Exchange under the hybrid algorithm, dt = 0.25, with master
    indicators on A: x falls through 0.5 at tau ln 2 = 0.3466 s (between the ticks of 0.3 and
    0.4, located by rollback inside a step holding ticks), and y falls through 0.5 at the tick
    of 0.4 (y jumps from exp(-0.6) to exp(-0.8) there: a crossing at a tick's instant, which
    localization approaches in pieces far shorter than the grid's rounding of a tick)."""
    first = signal("A")
    first.add_event_indicator("x_half", func=lambda c: c.get_outputs()["x"] - 0.5,
                              direction=-1)
    first.add_event_indicator("y_half", func=lambda c: c.get_outputs()["y"] - 0.5,
                              direction=-1)
    first.add_event_handler("noted", lambda *_: None)
    system = System("ticks and crossings")
    system.add_component(first)
    system.add_component(signal("B", tau=0.25))
    system.add_event_connection(EventConnection("A", "x_half", "A", "noted"))
    system.add_event_connection(EventConnection("A", "y_half", "A", "noted"))
    system.set_algorithm(HybridAlgorithm(tol_time=1e-10,
                                         coupling=JacobiAlgorithm(threads=threads)))
    system.initialize(0.0)
    events = system.run(0.0, 1.0, 0.25).events
    return [(e.t, e.micro, e.component, e.event) for e in events]


def test_ticks_and_crossings_in_one_step_are_recorded_in_superdense_order() -> None:
    records = ticks_and_crossings()
    by_name = {name: [r for r in records if r[3] == name]
               for name in ("clock_tick", "x_half", "y_half")}
    assert len(by_name["clock_tick"]) == 20  # A's and B's ticks at 0.1, ..., 1.0
    (x_half,), (y_half,) = by_name["x_half"], by_name["y_half"]
    assert x_half[0] == pytest.approx(TAU * math.log(2.0), abs=1e-9)
    # the crossing at the tick's instant is located within tol_time of it, after A's tick
    assert 0.4 <= y_half[0] <= 0.4 + 1e-10
    tick = next(r for r in records if r[2:] == ("A", "clock_tick") and abs(r[0] - 0.4) < 1e-12)
    assert records.index(tick) < records.index(y_half)
    assert records == sorted(records, key=lambda r: (r[0], r[1]))
    assert ticks_and_crossings() == records
    assert ticks_and_crossings(threads=2) == records
