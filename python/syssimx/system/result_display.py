"""How results show in a notebook: compact HTML tables (every text escaped), built without
pandas; the long lists (localization trials, every sample) stay in tables a user asks for."""

from __future__ import annotations

import html
from collections.abc import Iterable, Mapping, Sequence
from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    from .event_record import EventRecord


class Statistics(Protocol):
    """What the tables show of a run's statistics (results.Statistics)."""

    macro_steps: int
    do_step_calls: int
    state_saves: int
    state_restores: int
    events: int
    own_events: int
    localization_iterations: int
    loop_solves: int
    loop_iterations: int
    termination: Any


class SimulationResult(Protocol):
    """What the summary shows of a result (results.SimulationResult)."""

    system_name: str
    algorithm: str
    t0: float
    tf: float
    dt: float
    wall_time: float
    component_names: Sequence[str]
    units: Mapping[str, Mapping[str, str]]
    events: Sequence[EventRecord]
    statistics: Statistics

    def __getitem__(self, name: str) -> tuple[Any, Mapping[str, Any]]: ...

EVENTS_SHOWN = 10  # events listed in a result's table; the rest are counted


def html_table(header: Sequence[str], rows: Iterable[Sequence[Any]], caption: str = "") -> str:
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(_cell(c))}</td>" for c in row)
                   + "</tr>" for row in rows)
    title = f"<caption>{html.escape(caption)}</caption>" if caption else ""
    return f"<table>{title}<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _cell(value: Any) -> str:
    return f"{value:.10g}" if isinstance(value, float) else str(value)


def event_rows(events: Sequence[EventRecord], limit: int | None = None) -> list[list[Any]]:
    shown = events if limit is None else events[:limit]
    rows: list[list[Any]] = [[e.t, e.micro, f"{e.component}.{e.event}", e.iterations,
                              "own" if e.own else "located"] for e in shown]
    if limit is not None and len(events) > limit:
        rows.append(["…", "", f"{len(events) - limit} more", "", ""])
    return rows


EVENT_HEADER = ("t [s]", "micro", "event", "iterations", "how")


def events_html(events: Sequence[EventRecord], limit: int | None = EVENTS_SHOWN) -> str:
    return html_table(EVENT_HEADER, event_rows(events, limit), f"{len(events)} events")


def statistics_rows(statistics: Statistics) -> list[tuple[str, Any]]:
    rows: list[tuple[str, Any]] = [
        ("macro steps", statistics.macro_steps), ("doStep calls", statistics.do_step_calls),
        ("state saves / restores", f"{statistics.state_saves} / {statistics.state_restores}"),
        ("events located / handled by components",
         f"{statistics.events} / {statistics.own_events}"),
        ("localization iterations", statistics.localization_iterations),
        ("loop solves / iterations", f"{statistics.loop_solves} / {statistics.loop_iterations}"),
    ]
    if statistics.termination is not None:
        rows.append(("terminated", str(statistics.termination)))
    return rows


def statistics_html(statistics: Statistics) -> str:
    return html_table(("statistic", "value"), statistics_rows(statistics), "statistics")


def result_html(result: SimulationResult) -> str:
    """A summary: the run, the components and their samples, the events, the statistics."""
    run = html_table(("system", "algorithm", "t0 [s]", "tf [s]", "dt [s]", "wall time [s]"),
                     [(result.system_name, result.algorithm, result.t0, result.tf, result.dt,
                       f"{result.wall_time:.3g}")])
    components = []
    for name in result.component_names:
        t, ports = result[name]
        units = result.units.get(name, {})
        described = ", ".join(f"{p} [{units[p]}]" if units.get(p) else p for p in ports)
        components.append((name, len(t), described))
    parts = [run, html_table(("component", "samples", "ports"), components, "components")]
    if len(result.events):
        parts.append(events_html(result.events))
    parts.append(statistics_html(result.statistics))
    return "<div>" + "".join(parts) + "</div>"
