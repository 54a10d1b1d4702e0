"""`result.plot` on a real hybrid run: the seed's pendulum against the wall, three wall hits."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.image import imread
from scipy.special import ellipk
from syssimx import EventConnection, FMUComponent, HybridAlgorithm, System, fmus
from syssimx.viz.plot import EVENT_LINE

M, L, G, INERTIA, THETA0 = 40.0, 0.6, 9.81, 20.0, 0.5
# Quarter period of the pendulum released from rest at THETA0. The wall is elastic, so the hits
# come at t*, 3 t*, 5 t*, ...: three of them before 3 s.
QUARTER_PERIOD = ellipk(np.sin(THETA0 / 2) ** 2) / np.sqrt(M * G * L / INERTIA)
HITS = QUARTER_PERIOD * np.array([1.0, 3.0, 5.0])
DPI = 110  # what plot_result writes the PNG at


def bounce(component: FMUComponent, event_names: list[str], t: float) -> None:
    outputs = component.get_outputs()
    component.reinitialize(t, theta0=outputs["theta"].magnitude,
                           omega0=-outputs["omega"].magnitude)


def pendulum_against_the_wall() -> System:
    pendulum = FMUComponent("P", fmus.path("pendulum_cvode"), group="Mechanical")
    pendulum.set_parameters(theta0=THETA0, omega0=0.0, cvode_relative_tolerance=1e-10)
    pendulum.add_event_indicator("wall_hit", variable="theta", direction=-1)
    pendulum.add_event_handler("omega_invert", bounce)
    system = System("Pendulum against a wall")
    system.add_component(pendulum)
    system.add_event_connection(EventConnection("P", "wall_hit", "P", "omega_invert"))
    system.set_algorithm(HybridAlgorithm(tol_time=1e-9, tol_value=1e-9))
    system.initialize(0.0)
    return system


def test_plot_of_a_hybrid_run_marks_every_wall_hit(tmp_path: Path) -> None:
    system = pendulum_against_the_wall()
    result = system.run(0.0, 3.0, 0.05)
    event_times = np.array([event.t for event in result.events])
    # the run is the one described: the hits where the closed form puts them (CVODE at 1e-10)
    np.testing.assert_allclose(event_times, HITS, rtol=0, atol=1e-7)

    path = tmp_path / "pendulum.png"
    figure = result.plot(["P.theta", "P.omega"], path=path)

    image = imread(path)  # decodes as PNG
    width, height = figure.get_size_inches() * DPI
    assert image.shape[:2] == (round(height), round(width))
    assert image[..., :3].std() > 0.05  # something is drawn

    # theta [rad] and omega [rad/s]: one panel each, each with one dashed line per event
    assert [ax.get_ylabel() for ax in figure.axes] == ["[rad]", "[rad/s]"]
    t, data = result["P"]
    for ax, port in zip(figure.axes, ("theta", "omega"), strict=True):
        markers = [line for line in ax.lines if line.get_linestyle() == EVENT_LINE["linestyle"]]
        assert sorted(float(line.get_xdata()[0]) for line in markers) == event_times.tolist()
        signal = [line for line in ax.lines if line not in markers]
        assert len(signal) == 1
        np.testing.assert_array_equal(signal[0].get_ydata(), data[port])
        np.testing.assert_array_equal(signal[0].get_xdata(), t)
