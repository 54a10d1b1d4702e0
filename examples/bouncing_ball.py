"""A bouncing ball without subclassing: the FMU only falls, the master bounces it.

The floor indicator is the FMU output h (evaluated in C, no Python per step); a Python handler
reinitializes the FMU with the reversed, damped velocity. Prints the first bounce times
against the closed form and ends at the Zeno point with the documented error.

    python examples/bouncing_ball.py
"""

from __future__ import annotations

import math

from syssimx import EventConnection, FMUComponent, HybridAlgorithm, System, ZenoError, fmus

RESTITUTION, G, H0 = 0.8, 9.81, 1.0


def bounce(ball: FMUComponent, event_names: list[str], t: float) -> None:
    outputs = ball.get_outputs()
    ball.reinitialize(t, h0=outputs["h"].magnitude, v0=-RESTITUTION * outputs["v"].magnitude)


def build(fmu: str = "bouncing_ball_continuous_cvode", direction: int = -1,
          **parameters: float) -> System:
    """The ball dropped from H0 at rest, its floor indicator on h and the bounce handler
    (not initialized: choose the algorithm first)."""
    ball = FMUComponent("Ball", fmus.path(fmu))
    ball.set_parameters(h0=H0, v0=0.0, g=G, **parameters)
    ball.add_event_indicator("floor", variable="h", direction=direction)
    ball.add_event_handler("bounce", bounce)
    system = System("bouncing ball")
    system.add_component(ball)
    system.add_event_connection(EventConnection("Ball", "floor", "Ball", "bounce"))
    return system


def main() -> None:
    system = build(cvode_relative_tolerance=1e-12)
    # flights shorter than 0.1 ms count as chattering
    system.set_algorithm(HybridAlgorithm(tol_time=1e-10, zeno_min_interval=1e-4))
    system.initialize(0.0)

    t1 = math.sqrt(2 * H0 / G)
    v1 = G * t1
    try:
        system.run(0.0, 5.0, 0.01)
    except ZenoError as error:
        print(f"stopped: {error}")
    events = system.history.get_event_history("Ball", "floor")
    t_inf = t1 * (1 + RESTITUTION) / (1 - RESTITUTION)
    print(f"{len(events)} bounces; Zeno point t_inf = {t_inf:.6f} s")
    print(" n   located t [s]       closed form t [s]   difference")
    for n, event in enumerate(events[:10], start=1):
        exact = t1 + 2 * v1 / G * sum(RESTITUTION**k for k in range(1, n))
        print(f"{n:2d}   {event.t:.12f}    {exact:.12f}    {event.t - exact:+.1e}")


if __name__ == "__main__":
    main()
