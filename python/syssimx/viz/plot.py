"""Plots of a simulation result: chosen signals over time, event instants marked.

Uses matplotlib's object API with the Agg canvas, so it never opens a window and never touches
pyplot's global figure list.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ..core.suggest import did_you_mean
from ..errors import ConfigurationError


class ResultFigure(Figure):
    """A matplotlib Figure that a notebook shows as an image by itself: without pyplot, no
    `%matplotlib inline` registers a display for it."""

    def _repr_png_(self) -> bytes:
        buffer = io.BytesIO()
        self.savefig(buffer, format="png", dpi=90)
        return buffer.getvalue()


EVENT_LINE = {"color": "#c0392b", "linestyle": "--", "linewidth": 1.0, "alpha": 0.8}


def plot_result(
    result: Any,
    signals: Sequence[str],
    path: str | Path | None = None,
    events: bool = True,
) -> Figure:
    """Plot ``signals`` ("Component.port") of ``result``; write an image when ``path`` is given,
    in the format its suffix names (.png, .svg, .pdf, ...; PNG without one), as matplotlib does.
    The figure is returned, kept out of pyplot's list of figures (so it is not shown twice),
    and a notebook displays it as the last value of a cell.

    Signals sharing a unit share a subplot; a signal without a unit gets its own. With
    ``events``, every event instant of the run is a dashed vertical line.

    Args:
        result: a SimulationResult: ``result[component]`` -> ``(t, {port: values})``, and
            optionally ``units`` ({component: {port: unit}}) and ``events`` (records with
            ``t``, ``component``, ``name``).
        signals: what to plot, e.g. ``["P.theta", "P.omega"]``.
        path: where to write the image.
        events: mark the event instants.

    Raises:
        ConfigurationError: (also a ValueError) no signals, or a signal names an unknown
            component or port.
    """
    if not signals:
        raise ConfigurationError("plot_result needs at least one signal, e.g. 'Pendulum.theta'")
    series = [_series(result, signal) for signal in signals]
    panels: dict[str, list[tuple[str, np.ndarray, np.ndarray, str | None]]] = {}
    for signal, (t, values, unit) in zip(signals, series, strict=True):
        panels.setdefault(f"unit:{unit}" if unit else f"signal:{signal}", []).append(
            (signal, t, values, unit)
        )

    figure = ResultFigure(figsize=(8.0, 1.0 + 2.4 * len(panels)), layout="constrained")
    FigureCanvasAgg(figure)
    axes = figure.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    instants = _event_instants(result) if events else []
    event_label = "events: " + ", ".join(dict.fromkeys(label for _, label in instants))
    for ax, lines in zip(axes, panels.values(), strict=True):
        for signal, t, values, _ in lines:
            ax.plot(t, values, label=signal, marker=".", markersize=3, linewidth=1.2)
        for index, (t_event, _) in enumerate(instants):
            ax.axvline(t_event, label=event_label if index == 0 else None, **EVENT_LINE)
        unit = lines[0][3]
        ax.set_ylabel(f"[{unit}]" if unit else lines[0][0])
        ax.grid(True, alpha=0.4)
        ax.legend(loc="best", fontsize="small")
    axes[-1].set_xlabel("time [s]")
    title = getattr(result, "system_name", None)
    if title:
        figure.suptitle(str(title))
    if path is not None:
        from ..atomic_file import atomic_path

        # the temporary file has the target's suffix: matplotlib takes the format from it
        with atomic_path(path) as temporary:
            figure.savefig(temporary, dpi=110)
    return figure


def _series(result: Any, signal: str) -> tuple[np.ndarray, np.ndarray, str | None]:
    component, port = _split_signal(result, signal)
    try:
        t, values = result[component]
    except KeyError:
        names = getattr(result, "component_names", None) or []
        raise ConfigurationError(f"signal {signal!r}: no component {component!r} in the result"
                                 f"{did_you_mean(component, names)}") from None
    if port not in values:
        known = ", ".join(values) or "none"
        raise ConfigurationError(f"signal {signal!r}: {component!r} has no port {port!r}"
                                 f"{did_you_mean(port, values)}; ports: {known}")
    units = getattr(result, "units", None) or {}
    unit = units.get(component, {}).get(port)
    return np.asarray(t, dtype=float), np.asarray(values[port], dtype=float), unit or None


def _split_signal(result: Any, signal: str) -> tuple[str, str]:
    """Split "Component.port" at the longest known component name (ports may contain dots)."""
    names = getattr(result, "component_names", None) or []
    matches = [name for name in names if signal.startswith(f"{name}.")]
    if matches:
        name = max(matches, key=len)
        return name, signal[len(name) + 1 :]
    component, dot, port = signal.partition(".")
    if not dot or not component or not port:
        raise ConfigurationError(f"signal {signal!r} is not of the form 'Component.port'")
    return component, port


def _event_instants(result: Any) -> list[tuple[float, str]]:
    """Distinct event times with the events that happened there, in time order."""
    names: dict[float, list[str]] = {}
    for record in getattr(result, "events", None) or []:
        label = f"{record.component}.{record.name}"
        at = names.setdefault(float(record.t), [])
        if label not in at:
            at.append(label)
    return [(t, ", ".join(labels)) for t, labels in sorted(names.items())]
