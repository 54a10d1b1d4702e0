"""Model switching (MultiComponent, SwitchRegions, ModeSwitchEvent, result.mode_switches):
switches located as events, with state transfer, against closed forms."""

from __future__ import annotations

import math
import re
import runpy
from pathlib import Path
from typing import Any

import model_switching  # examples/: free fall FMU -> parachute model
import numpy as np
import pytest
from syssimx import (
    CoSimComponent,
    EventConnection,
    HybridAlgorithm,
    ModeSwitchEvent,
    MultiComponent,
    PortSpec,
    PortType,
    SimulationError,
    SwitchRegions,
    System,
)
from syssimx.errors import ConfigurationError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

HEAT, COOL, BREAKPOINT, BAND = 0.7, 1.3, 1.0, 0.1


class Ramp(CoSimComponent):
    """x' = rate from x0, stepped exactly."""

    def __init__(self, name: str, rate: float) -> None:
        super().__init__(name)
        self.output_specs["x"] = PortSpec("x", PortType.REAL, "out", "K")
        self.parameters = {"x0": 0.0, "rate": rate}
        self.x = 0.0
        self.steps = 0

    def _initialize_component(self, t0: float) -> None:
        self.x = float(self.parameters["x0"])

    def _do_step_internal(self, t: float, dt: float) -> None:
        self.x += self.parameters["rate"] * dt
        self.steps += 1

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        self.outputs["x"].set(self.x, t)

    def snapshot_state(self) -> float:
        return self.x

    def restore_state(self, snapshot: float, t: float) -> None:
        self.x = snapshot


class Thermostat(MultiComponent):
    """Heats below the breakpoint, cools above it; the band is the hysteresis."""

    def __init__(self, name: str = "T") -> None:
        super().__init__(name, {"heating": Ramp("heater", HEAT), "cooling": Ramp("cooler", -COOL)},
                         initial_mode="heating")

    def _adapt_state(self, state: dict[str, Any], target_mode: str) -> dict[str, Any]:
        return {"x0": state["x"]}


def thermostat_switch_times(count: int) -> list[float]:
    """From x = 0: up to 1 + band at HEAT, then down to 1 - band at COOL, up again, ..."""
    times = [(BREAKPOINT + BAND) / HEAT]
    for k in range(1, count):
        times.append(times[-1] + 2 * BAND / (COOL if k % 2 else HEAT))
    return times


def thermostat_system(regions: bool = True) -> tuple[System, Thermostat]:
    thermostat = Thermostat()
    if regions:
        thermostat.set_switch_regions(lambda c: c.outputs["x"].raw(), [BREAKPOINT],
                                      ["heating", "cooling"], BAND)
    system = System("thermostat")
    system.add_component(thermostat)
    system.set_algorithm(HybridAlgorithm(tol_time=1e-11, tol_value=1e-12))
    return system, thermostat


def test_switches_both_ways_at_the_closed_form_times():
    system, thermostat = thermostat_system()
    system.initialize(0.0)
    result = system.run(0.0, 3.0, 0.05)
    expected = thermostat_switch_times(8)
    expected = [t for t in expected if t <= 3.0]
    switches = result.mode_switches["T"]
    assert [s.from_mode for s in switches] == ["heating", "cooling"] * (len(expected) // 2) \
        + ["heating"] * (len(expected) % 2)
    # each switch restarts the next model from the located state: errors add up over 7 switches
    np.testing.assert_allclose([s.time for s in switches], expected, rtol=0, atol=1e-9)
    assert switches == thermostat.switch_events == thermostat.history.mode_switch_events
    assert system.get_history()["ModeSwitches"] == {"T": switches}
    assert all(isinstance(s, ModeSwitchEvent) and s.source_state is None for s in switches)
    # the events are the generated region boundary, located like any event
    assert [e.event for e in result.events] == ["region_boundary_0"] * len(expected)
    assert result.events.keys() == [("T", "region_boundary_0")]
    # state transfer: the wrapper's output is continuous, a triangle wave between the band edges
    t, values = result["T"]
    x = values["x"]
    first = expected[0]
    assert x.max() <= BREAKPOINT + BAND + 1e-9
    assert x[t >= first].min() >= BREAKPOINT - BAND - 1e-9
    np.testing.assert_allclose(x[t <= first], HEAT * t[t <= first], rtol=0, atol=1e-12)
    between = (t > first) & (t <= expected[1])
    np.testing.assert_allclose(x[between], BREAKPOINT + BAND - COOL * (t[between] - first),
                               rtol=0, atol=1e-9)


def test_switch_records_carry_the_states_when_asked():
    system, thermostat = thermostat_system()
    thermostat.record_switch_state = True
    system.initialize(0.0)
    result = system.run(0.0, 1.7, 0.05)
    (switch,) = result.mode_switches["T"]
    assert switch.source_state["x"]["value"] == pytest.approx(BREAKPOINT + BAND, abs=1e-9)
    assert switch.target_state["x"]["value"] == switch.source_state["x"]["value"]
    assert switch.target_state["rate"]["value"] == -COOL
    assert thermostat.active_mode == "cooling" and thermostat.active_region_index == 1


def test_the_initial_region_picks_the_model():
    system, thermostat = thermostat_system()
    thermostat.models["heating"].set_parameters(x0=1.05)  # above the breakpoint: cooling
    system.initialize(0.0)
    assert (thermostat.active_mode, thermostat.active_region_index) == ("cooling", 1)
    result = system.run(0.0, 0.1, 0.05)
    t, values = result["T"]
    np.testing.assert_allclose(values["x"], 1.05 - COOL * t, rtol=0, atol=1e-12)
    assert result.mode_switches == {}
    # then down to the lower band edge and back to heating
    result = system.run(0.1, 0.2, 0.05)
    (switch,) = result.mode_switches["T"]
    assert (switch.from_mode, switch.to_mode) == ("cooling", "heating")
    assert switch.time == pytest.approx((1.05 - (BREAKPOINT - BAND)) / COOL, abs=1e-10)


def test_free_fall_fmu_hands_over_to_the_parachute_model():
    system, _ = model_switching.build()
    result = system.run(0.0, 3.0, 0.05)
    g, h0, low = model_switching.G, model_switching.H0, \
        model_switching.BREAKPOINT - model_switching.BAND
    t_switch = math.sqrt(2 * (h0 - low) / g)
    (switch,) = result.mode_switches["Load"]
    assert (switch.from_mode, switch.to_mode) == ("free_fall", "parachute")
    assert switch.time == pytest.approx(t_switch, abs=1e-9)
    t, values = result["Load"]
    falling = t < switch.time
    np.testing.assert_allclose(values["h"][falling], h0 - g * t[falling] ** 2 / 2, rtol=0,
                               atol=1e-9)
    descending = t > switch.time
    np.testing.assert_allclose(values["h"][descending],
                               low - model_switching.V_DESCENT * (t[descending] - t_switch),
                               rtol=0, atol=1e-8)
    np.testing.assert_array_equal(values["v"][descending], -model_switching.V_DESCENT)


def test_switching_by_hand_from_an_event_handler():
    thermostat = Thermostat()
    thermostat.add_event_indicator("hot", lambda c: c.outputs["x"].raw() - 0.5, direction=1)

    def cool_down(component: MultiComponent, events: list[str], t: float) -> None:
        component._switch_mode("cooling", t)

    thermostat.add_event_handler("switch", cool_down)
    system = System("by hand")
    system.add_component(thermostat)
    system.add_event_connection(EventConnection("T", "hot", "T", "switch"))
    system.set_algorithm(HybridAlgorithm(tol_time=1e-11))
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.1)
    (switch,) = result.mode_switches["T"]
    assert switch.time == pytest.approx(0.5 / HEAT, abs=1e-10)
    assert result["T"][1]["x"][-1] == pytest.approx(0.5 - COOL * (1.0 - 0.5 / HEAT), abs=1e-9)


def test_regions_and_models_are_checked():
    with pytest.raises(ValueError, match=r"2 modes need 1 breakpoints, got 2"):
        SwitchRegions(lambda c: 0.0, [1.0, 2.0], ["a", "b"], 0.1)
    with pytest.raises(ValueError, match=r"bands of neighbouring breakpoints overlap"):
        SwitchRegions(lambda c: 0.0, [1.0, 1.1], ["a", "b", "a"], 0.1)
    with pytest.raises(ValueError, match=r"neighbouring regions use the same model"):
        SwitchRegions(lambda c: 0.0, [1.0], ["a", "a"], 0.1)
    with pytest.raises(ConfigurationError, match=r"T: regions name unknown models \['boiling'\]"):
        Thermostat().set_switch_regions(SwitchRegions(lambda c: 0.0, [1.0],
                                                      ["heating", "boiling"], 0.1))
    other = Ramp("other", 1.0)
    other.output_specs["x"] = PortSpec("x", PortType.REAL, "out", "m")
    with pytest.raises(ConfigurationError, match=r"T: output 'x' of model 'b' has unit 'm', not "
                       r"convertible to 'K'"):
        MultiComponent("T", {"a": Ramp("a", 1.0), "b": other}, "a")
    with pytest.raises(ConfigurationError, match=r"initial_mode 'c' is not one of the models"):
        MultiComponent("T", {"a": Ramp("a", 1.0)}, "c")


def test_a_missing_state_translation_names_the_component():
    thermostat = MultiComponent("T", {"heating": Ramp("h", HEAT), "cooling": Ramp("c", -COOL)},
                                "heating")
    thermostat.set_switch_regions(lambda c: c.outputs["x"].raw(), [BREAKPOINT],
                                  ["heating", "cooling"], BAND)
    system = System("untranslated")
    system.add_component(thermostat)
    system.initialize(0.0)
    with pytest.raises(SimulationError, match=r"T: a MultiComponent subclass implements "
                       r"_adapt_state\(state, target_mode\)"):
        system.run(0.0, 2.0, 0.1)
    assert thermostat.active_mode == "heating"  # nothing was committed


def test_the_example_prints_the_switch_against_its_closed_form(
        capsys: pytest.CaptureFixture[str]):
    runpy.run_path(str(EXAMPLES / "model_switching.py"), run_name="__main__")
    switch, height = capsys.readouterr().out.splitlines()
    assert switch.startswith("free_fall -> parachute at t = 1.1106013")
    assert abs(float(switch.split("difference ")[1].split()[0])) < 1e-9
    located, exact = (float(x) for x in re.findall(r"(-?\d+\.\d{6,}) m", height))
    assert located == pytest.approx(exact, abs=1e-8)
