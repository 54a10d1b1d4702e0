"""Model switching: a falling load whose parachute opens below a height, with state transfer.

One component, two models: free fall (the bundled CVODE FMU bouncing_ball_continuous, h'' = -g)
above the breakpoint and a Python model of steady descent under the parachute
(h' = -V_DESCENT) below it. SwitchRegions turns the boundary into an event indicator, so the
switch is located like any event (at h = BREAKPOINT - BAND, the band's far edge) and the
parachute model starts from the height the FMU reached there. Closed form:

    t_switch = sqrt(2 (H0 - (BREAKPOINT - BAND)) / g),   h(t) = BREAKPOINT - BAND - V (t - t_switch)

    python examples/model_switching.py
"""

from __future__ import annotations

import math
from typing import Any

from syssimx import (
    CoSimComponent,
    FMUComponent,
    HybridAlgorithm,
    MultiComponent,
    PortSpec,
    PortType,
    SwitchRegions,
    System,
    fmus,
)

G, H0, BREAKPOINT, BAND, V_DESCENT = 9.81, 10.0, 4.0, 0.05, 2.0


class SteadyDescent(CoSimComponent):
    """h' = -v_descent from h0: the load under its open parachute (exact steps)."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.output_specs.update({"h": PortSpec("h", PortType.REAL, "out", "m"),
                                  "v": PortSpec("v", PortType.REAL, "out", "m/s")})
        self.parameters = {"h0": 0.0, "v_descent": V_DESCENT}
        self.h = 0.0

    def _initialize_component(self, t0: float) -> None:
        self.h = float(self.parameters["h0"])

    def _do_step_internal(self, t: float, dt: float) -> None:
        self.h -= self.parameters["v_descent"] * dt

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        self.outputs["h"].set(self.h, t)
        self.outputs["v"].set(-self.parameters["v_descent"], t)

    def snapshot_state(self) -> float:
        return self.h

    def restore_state(self, snapshot: float, t: float) -> None:
        self.h = snapshot


class Load(MultiComponent):
    """Free fall above the breakpoint, steady descent below it."""

    def __init__(self, name: str) -> None:
        fall = FMUComponent(f"{name}.fall", fmus.path("bouncing_ball_continuous_cvode"))
        fall.set_parameters(h0=H0, v0=0.0, g=G, cvode_relative_tolerance=1e-12)
        super().__init__(name, {"free_fall": fall, "parachute": SteadyDescent(f"{name}.chute")},
                         initial_mode="free_fall")
        self.set_switch_regions(SwitchRegions(
            key=lambda load: load.outputs["h"].raw(), breakpoints=[BREAKPOINT],
            modes=["parachute", "free_fall"], band=BAND))

    def _adapt_state(self, state: dict[str, Any], target_mode: str) -> dict[str, Any]:
        """Only the height carries over: the parachute sets the speed, free fall keeps it."""
        if target_mode == "parachute":
            return {"h0": state["h"]}
        return {"h0": state["h"], "v0": state["v"]}


def build() -> tuple[System, Load]:
    load = Load("Load")
    system = System("parachute")
    system.add_component(load)
    system.set_algorithm(HybridAlgorithm(tol_time=1e-10))
    system.initialize(0.0)
    return system, load


def main() -> None:
    system, _ = build()
    result = system.run(0.0, 3.0, 0.05)
    t_switch = math.sqrt(2 * (H0 - (BREAKPOINT - BAND)) / G)
    for switch in result.mode_switches["Load"]:
        print(f"{switch.from_mode} -> {switch.to_mode} at t = {switch.time:.12f} s "
              f"(closed form {t_switch:.12f} s, difference {switch.time - t_switch:+.1e} s)")
    t, values = result["Load"]
    h_exact = BREAKPOINT - BAND - V_DESCENT * (t[-1] - t_switch)
    print(f"h({t[-1]:g} s) = {values['h'][-1]:.12f} m (closed form {h_exact:.12f} m)")


if __name__ == "__main__":
    main()
