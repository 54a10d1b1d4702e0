"""Result plots: the PNG decodes, and the drawn data are the result's data."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from matplotlib.image import imread
from syssimx.viz.plot import EVENT_LINE, plot_result


@dataclass(frozen=True)
class EventRecord:
    t: float
    component: str
    name: str


class StandInResult:
    """What plot_result reads from a SimulationResult."""

    system_name = "Pendulum against a wall"

    def __init__(self) -> None:
        t = np.linspace(0.0, 1.0, 21)
        self.t = t
        self.data = {
            "P": {"theta": 0.5 * np.cos(3.0 * t), "omega": -1.5 * np.sin(3.0 * t),
                  "contact": (t > 0.5).astype(float)},
            "P.arm": {"x.tip": 0.6 * np.sin(t)},  # a dotted component and a dotted port
        }
        self.units = {"P": {"theta": "rad", "omega": "rad/s", "contact": None},
                      "P.arm": {"x.tip": "rad"}}
        self.events = [EventRecord(0.465, "P", "wall_hit"), EventRecord(0.465, "P", "wall_hit"),
                       EventRecord(0.9, "P", "wall_hit")]

    @property
    def component_names(self) -> list[str]:
        return list(self.data)

    def __getitem__(self, component: str) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        return self.t, self.data[component]


def test_png_is_written_and_holds_a_real_picture(tmp_path: Path) -> None:
    result = StandInResult()
    path = tmp_path / "plot.png"
    figure = plot_result(result, ["P.theta", "P.omega", "P.contact", "P.arm.x.tip"], path=path)
    image = imread(path)
    width, height = figure.get_size_inches() * 110
    assert image.shape[:2] == (round(height), round(width))
    assert image[..., :3].std() > 0.05  # not a blank canvas

    # theta and the tip share "rad"; omega and the unitless contact get their own panels.
    axes = figure.axes
    assert [ax.get_ylabel() for ax in axes] == ["[rad]", "[rad/s]", "P.contact"]
    signal_lines = [line for line in axes[0].lines
                    if line.get_linestyle() != EVENT_LINE["linestyle"]]
    assert [line.get_label() for line in signal_lines] == ["P.theta", "P.arm.x.tip"]
    np.testing.assert_array_equal(signal_lines[0].get_ydata(), result.data["P"]["theta"])
    np.testing.assert_array_equal(signal_lines[1].get_xdata(), result.t)


def test_event_instants_are_vertical_lines_once_each() -> None:
    figure = plot_result(StandInResult(), ["P.theta"])
    event_lines = [line for line in figure.axes[0].lines
                   if line.get_linestyle() == EVENT_LINE["linestyle"]]
    assert [line.get_xdata()[0] for line in event_lines] == [0.465, 0.9]
    assert event_lines[0].get_label() == "events: P.wall_hit"
    assert len(plot_result(StandInResult(), ["P.theta"], events=False).axes[0].lines) == 1


@pytest.mark.parametrize(
    ("signals", "message"),
    [
        ([], "at least one signal"),
        (["theta"], "not of the form"),
        (["Q.theta"], "no component 'Q'"),
        (["P.phi"], "ports: theta, omega, contact"),
    ],
)
def test_bad_signals_are_named(signals: list[str], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        plot_result(StandInResult(), signals)
