"""What a notebook shows: a plot as the figure itself (kept out of pyplot's list), in the format
a file's suffix names; systems, results, statistics, events and ensembles as HTML tables or
short text, never an exception; a missing optional library naming the extra to install."""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest
from syssimx import SysSimXError
from syssimx.ensemble.member import MemberResult
from syssimx.ensemble.result import EnsembleResult
from syssimx.errors import MissingDependencyError
from syssimx.system.loader import build_system

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
# Quarter period of the seed pendulum released at 0.5 rad: ellipk(sin^2(0.25)) / sqrt(mgL/I).
EXACT_WALL_TIME = 0.46507759431173046


@pytest.fixture(scope="module")
def wall():
    system = build_system(EXAMPLES / "pendulum_wall.yaml")
    system.initialize(0.0)
    return system, system.run(0.0, 2.0, 0.05)


def test_plot_returns_a_figure_a_notebook_shows_once(wall):
    _, result = wall
    before = plt.get_fignums()
    figure = result.plot(["P.theta", "P.omega"])
    assert figure._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"  # shown without %matplotlib
    assert plt.get_fignums() == before  # not in pyplot's list: not shown a second time
    assert len(figure.axes) == 2


@pytest.mark.parametrize(("suffix", "magic"), [(".svg", b"<?xml"), (".pdf", b"%PDF"),
                                               (".png", b"\x89PNG"), (".jpg", b"\xff\xd8")])
def test_the_suffix_decides_the_format(wall, tmp_path: Path, suffix: str, magic: bytes):
    _, result = wall
    path = tmp_path / f"figure{suffix}"
    result.plot(["P.theta"], path=path)
    assert path.read_bytes()[:len(magic)] == magic


def test_a_system_without_graphviz_shows_as_text(wall, monkeypatch: pytest.MonkeyPatch):
    system, _ = wall
    monkeypatch.setitem(sys.modules, "graphviz", None)  # what an import of a missing one does
    monkeypatch.delitem(sys.modules, "syssimx.viz.system_graph_visualizer", raising=False)
    assert system._repr_svg_() is None  # Jupyter then shows the text repr
    assert repr(system).startswith("System(")


def test_a_system_without_the_dot_program_shows_as_text(wall, monkeypatch: pytest.MonkeyPatch):
    pytest.importorskip("graphviz")
    system, _ = wall
    monkeypatch.setenv("PATH", "")
    assert system._repr_svg_() is None


def test_result_html_has_components_events_and_statistics(wall):
    _, result = wall
    page = result._repr_html_()
    t = result["P"][0]
    assert "pendulum against a wall" in page and "HybridAlgorithm" in page
    assert f"<td>P</td><td>{len(t)}</td><td>theta [rad], omega [rad/s]" in page
    assert f"{len(result.events)} events" in page
    first = result.events[0]
    assert abs(first.t - EXACT_WALL_TIME) < 1e-8  # CVODE at rtol 1e-10, bracket 1e-9
    assert f"<td>{first.t:.10g}</td><td>0</td><td>P.wall_hit</td>" in page
    assert f"<td>macro steps</td><td>{result.statistics.macro_steps}</td>" in page
    assert "<td>macro steps</td>" in result.statistics._repr_html_()
    assert page.count("<tr>") < 40  # compact: no sample and no trial listed


def test_an_events_repr_is_one_line_and_its_trials_a_table_on_request(wall):
    _, result = wall
    event = result.events[0]
    assert len(event.trials) > 1
    text = repr(event)
    assert text == str(event) and "\n" not in text and len(text) < 120
    assert text.startswith(f"EventRecord(P.wall_hit at t={event.t!r}, micro=0, ")
    trials = result.events.trials()
    assert len(trials) == sum(len(e.trials) for e in result.events)
    first = trials[trials["event"] == 0]
    assert first["t"].tolist() == [trial.t for trial in event.trials]
    assert result.events._repr_html_().count("P.wall_hit") == len(result.events)


def test_ensemble_result_html_lists_members_and_counts_the_rest():
    members = [MemberResult(i, {"P.theta0": 0.1 * i}, "ok" if i != 3 else "failed",
                            error="SimulationError: boom" if i == 3 else "",
                            time=np.linspace(0.0, 1.0, 11))
               for i in range(12)]
    result = EnsembleResult(members, ["P.theta0"], 0.0, 1.0, 0.1, 2.5)
    page = result._repr_html_()
    assert "<td>12</td><td>11</td><td>1</td><td>P.theta0</td>" in page
    assert "<td>3</td><td>0.3</td><td>failed</td><td>11</td><td>SimulationError: boom</td>" \
        in page.replace("0.30000000000000004", "0.3")
    assert "2 more" in page
    assert repr(result) == ("EnsembleResult(12 members, 1 failed, parameters=['P.theta0'], "
                            "wall_time=2.5 s)")


def test_a_missing_optional_library_names_the_extra(wall, monkeypatch: pytest.MonkeyPatch):
    _, result = wall
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(MissingDependencyError) as raised:
        result.to_dataframe()
    assert str(raised.value) == ("SimulationResult.to_dataframe needs pandas, which is not "
                                 'installed: pip install "syssimx-engine[results]"')
    assert isinstance(raised.value, SysSimXError) and isinstance(raised.value, ImportError)
    monkeypatch.setitem(sys.modules, "xarray", None)
    ensemble = EnsembleResult([], [], 0.0, 1.0, 0.1, 0.0)
    with pytest.raises(MissingDependencyError, match=r'pip install "syssimx-engine\[ensemble\]"'):
        ensemble.grid()


def test_an_fmu_component_shows_its_fmu_version_interface_and_ports_with_units():
    from syssimx import FMUComponent, fmus

    ball = FMUComponent("ball", fmus.path("bouncing_ball_cvode"))
    assert repr(ball) == ("FMUComponent('ball', bouncing_ball_cvode.fmu, FMI 2.0 co-simulation, "
                          "inputs: none; outputs: h [m], v [m/s])")
    page = ball._repr_html_()
    assert f"<tr><th>FMU</th><td>{ball.fmu_path}</td></tr>" in page
    assert "<tr><th>FMI version</th><td>2.0</td></tr>" in page
    assert "<tr><th>interface</th><td>co-simulation</td></tr>" in page
    assert "<tr><th>outputs</th><td>h [m], v [m/s]</td></tr>" in page
    pendulum = FMUComponent("P", fmus.path("pendulum_cvode_fmi3"), interface="model-exchange")
    assert "FMI 3.0 model-exchange, inputs: torque [N.m]; outputs: theta [rad]" in repr(pendulum)


class _Printer:
    """IPython's pretty printer, as far as _repr_pretty_ uses it."""

    def __init__(self) -> None:
        self.shown = ""

    def text(self, text: str) -> None:
        self.shown += text


def test_a_system_without_graphviz_says_how_to_get_its_picture(
        wall, monkeypatch: pytest.MonkeyPatch):
    system, _ = wall
    monkeypatch.setitem(sys.modules, "graphviz", None)
    printer = _Printer()
    system._repr_pretty_(printer, False)
    first, hint = printer.shown.split("\n")
    assert first == repr(system)
    assert 'pip install "syssimx-engine[viz]"' in hint and "apt install graphviz" in hint


def test_a_system_that_can_be_drawn_shows_only_its_repr_as_text(wall):
    pytest.importorskip("graphviz")
    system, _ = wall
    printer = _Printer()
    system._repr_pretty_(printer, False)
    assert printer.shown == repr(system)
