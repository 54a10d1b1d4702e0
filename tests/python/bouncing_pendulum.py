"""What the clock tests share: the seed pendulum (theta0 = 0.5, the CVODE pendulum bounced off
the wall at theta = 0) placed beside clocked FMUs, whose first wall hit must stay where it is
alone, and a Python component that keeps the system from rolling back."""

from __future__ import annotations

from syssimx import CoSimComponent, EventConnection, FMUComponent, Reinitialize, System, fmus

# the quarter period of the seed pendulum (theta0 = 0.5): its first wall hit (DESIGN.md)
WALL_HIT = 0.46507759431173046


def add_bouncing_pendulum(system: System, name: str = "P") -> FMUComponent:
    """Adds the seed pendulum as `name`, its indicator `wall_hit` connected to its own handler
    `bounce` (theta and omega reinitialized, omega reversed)."""
    pendulum = FMUComponent(name, fmus.path("pendulum_cvode_fmi3"), tolerance=1e-10)
    pendulum.set_parameters(theta0=0.5)
    pendulum.add_event_indicator("wall_hit", variable="theta", direction=-1)
    pendulum.add_event_handler("bounce", Reinitialize(theta0="theta", omega0="-omega"))
    system.add_component(pendulum)
    system.add_event_connection(EventConnection(name, "wall_hit", name, "bounce"))
    return pendulum


class Passive(CoSimComponent):
    """A Python component without snapshot_state: the system cannot roll back."""

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        pass
