"""The engine schedule: SysSimX's Gauss-Seidel semantics on the engine's sequential stepping.

SysSimX orders components in generations of the zero-delay (direct feedthrough) graph and sets
every input of a generation before any member of it steps. A delayed connection between two
members of one generation therefore carries the value of the start of the macro step. The
engine's Gauss-Seidel steps one group after the other, handing each its producers' newest
outputs, so inside a generation consumers are placed before their producers wherever the
delayed connections allow it (a cycle of delayed connections cannot be ordered so; there the
connection given first wins).
"""

from __future__ import annotations

from collections.abc import Sequence

import networkx as nx

from ..graph.analysis import SystemAnalysis

ConnectionKey = tuple[str, str, str, str]


def engine_schedule(analysis: SystemAnalysis, names: Sequence[str],
                    connections: Sequence[ConnectionKey]
                    ) -> tuple[list[str], list[int], list[bool]]:
    """(order, group sizes, group is a loop) for ssx_set_schedule."""
    added = {name: i for i, name in enumerate(names)}
    loops = [list(loop) for loop in analysis.loops]
    loop_of = {name: i for i, loop in enumerate(loops) for name in loop}
    units: list[list[str]] = [list(loop) for loop in loops]
    units += [[name] for name in names if name not in loop_of]
    unit_of = {name: i for i, unit in enumerate(units) for name in unit}

    zero_delay = nx.DiGraph()
    zero_delay.add_nodes_from(range(len(units)))
    for src, dst in analysis.graph.edges:
        if unit_of[src] != unit_of[dst]:
            zero_delay.add_edge(unit_of[src], unit_of[dst])

    def first(unit: int) -> int:
        return min(added[name] for name in units[unit])

    order: list[str] = []
    sizes: list[int] = []
    is_loop: list[bool] = []
    for generation in nx.topological_generations(zero_delay):
        members = set(generation)
        within = nx.DiGraph()
        within.add_nodes_from(members)
        for src, _, dst, _ in connections:
            producer, consumer = unit_of[src], unit_of[dst]
            if producer == consumer or producer not in members or consumer not in members:
                continue
            if not nx.has_path(within, producer, consumer):
                within.add_edge(consumer, producer)
        for unit in nx.lexicographical_topological_sort(within, key=first):
            order.extend(units[unit])
            sizes.append(len(units[unit]))
            is_loop.append(unit < len(loops))
    return order, sizes, is_loop
