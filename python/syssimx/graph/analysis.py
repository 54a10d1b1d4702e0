"""Data-flow analysis of a system: zero-delay dependencies, algebraic loops, execution order.

A connection ``src.o -> dst.i`` is *zero-delay* when ``dst`` computes one of its connected
outputs from ``i`` without delay (direct feedthrough): the value ``dst`` passes on at a
communication point then depends on the value ``src`` produces at that same point, so ``src``
must be evaluated first. A cycle of zero-delay connections is an algebraic loop, which the
engine solves at every communication point.

Execution follows SysSimX's Gauss-Seidel semantics: components run in topological generations of
the zero-delay graph, and a delayed connection inside one generation carries the value of the
start of the macro step. The engine steps one group after the other and hands each its
producers' newest outputs, so inside a generation consumers run before their producers wherever
the delayed connections allow it (in a cycle of delayed connections, the connection given first
decides).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..core.suggest import did_you_mean
from ..errors import ConfigurationError
from .digraph import generations as topological_generations
from .digraph import lexicographic_order, reaches, strongly_connected

if TYPE_CHECKING:
    import networkx as nx

ConnectionKey = tuple[str, str, str, str]
"""(src_comp, src_port, dst_comp, dst_port)"""

FeedthroughMap = Mapping[str, set[str]]
"""output port -> the input ports it reads without delay"""


@dataclass(frozen=True)
class SystemAnalysis:
    """The structure the engine is scheduled from.

    Attributes:
        components: every component, in the order added.
        zero_delay: (src, dst) -> the connections behind that zero-delay dependency.
        generations: Gauss-Seidel execution order in generations (topological generations of the
            zero-delay graph's condensation); the members of one algebraic loop are adjacent,
            and inside a generation consumers precede their delayed producers.
        loops: the algebraic loops, each a list of components (a single component when its own
            feedthrough output feeds its own input).
        order: every component once, the generations flattened.
        loop_connections: the zero-delay connections inside the loops (the tear variables).
    """

    components: list[str]
    zero_delay: dict[tuple[str, str], list[ConnectionKey]]
    generations: list[list[str]]
    loops: list[list[str]]
    order: list[str]
    loop_connections: list[ConnectionKey]

    @property
    def graph(self) -> nx.DiGraph:
        """Components as nodes, one edge per zero-delay dependency with the edge attribute
        ``connections`` (networkx is imported here, for whoever wants its graph)."""
        import networkx as nx

        graph = nx.DiGraph()
        graph.add_nodes_from(self.components)
        for (src, dst), connections in self.zero_delay.items():
            graph.add_edge(src, dst, connections=list(connections))
        return graph

    def schedule(self) -> tuple[list[str], list[int], list[bool]]:
        """(order, group sizes, group is a loop), the arguments of the engine's ssx_set_schedule.

        Each loop is one group; every other component is a group of its own.
        """
        loop_of = {name: index for index, loop in enumerate(self.loops) for name in loop}
        sizes: list[int] = []
        is_loop: list[bool] = []
        emitted: set[int] = set()
        for name in self.order:
            index = loop_of.get(name)
            if index is None:
                sizes.append(1)
                is_loop.append(False)
            elif index not in emitted:
                emitted.add(index)
                sizes.append(len(self.loops[index]))
                is_loop.append(True)
        return list(self.order), sizes, is_loop


def analyze(
    components: Mapping[str, FeedthroughMap], connections: Sequence[ConnectionKey]
) -> SystemAnalysis:
    """Analyze a system given as feedthrough maps per component and its data connections.

    Args:
        components: component name -> {output port: input ports it depends on without delay},
            in the order the components were added (the tie-break of the execution order).
        connections: (src_comp, src_port, dst_comp, dst_port) for every data connection.

    Raises:
        ConfigurationError: (also a ValueError) a connection names a component that is not in
            ``components``.
    """
    names = list(components)
    for connection in connections:
        for name in (connection[0], connection[2]):
            if name not in components:
                known = ", ".join(names) or "none"
                raise ConfigurationError(
                    f"connection {_format_connection(connection)} names the unknown component "
                    f"{name!r}{did_you_mean(name, names)}; components: {known}"
                )

    zero_delay = _zero_delay_edges(components, connections)
    successors: dict[str, list[str]] = {}
    for src, dst in zero_delay:
        successors.setdefault(src, []).append(dst)
    added = {name: i for i, name in enumerate(names)}
    sccs = sorted(
        (sorted(scc, key=added.__getitem__) for scc in strongly_connected(names, successors)),
        key=lambda members: added[members[0]],
    )
    loops = [scc for scc in sccs if len(scc) > 1 or (scc[0], scc[0]) in zero_delay]
    generations = _generations(zero_delay, sccs, connections)
    order = [name for generation in generations for name in generation]
    position = {name: index for index, name in enumerate(order)}
    loops.sort(key=lambda loop: position[loop[0]])

    loop_members = {name: index for index, loop in enumerate(loops) for name in loop}
    loop_connections = [
        connection
        for (src, dst), behind in zero_delay.items()
        if src in loop_members and loop_members[src] == loop_members.get(dst)
        for connection in behind
    ]
    given_order = {connection: i for i, connection in enumerate(connections)}
    loop_connections.sort(key=given_order.__getitem__)
    return SystemAnalysis(names, zero_delay, generations, loops, order, loop_connections)


def analyze_system(system: Any) -> SystemAnalysis:
    """Analyze a System from its components' feedthrough and its ``connections``.

    A component's feedthrough is its ``feedthrough()`` (what the System schedules with) when it
    has one, else its declared ``direct_feedthrough``.
    """
    components = {name: _feedthrough_of(component)
                  for name, component in system.components.items()}
    connections = [
        (c.src_comp, c.src_port, c.dst_comp, c.dst_port) for c in system.connections
    ]
    return analyze(components, connections)


def _feedthrough_of(component: Any) -> FeedthroughMap:
    method = getattr(component, "feedthrough", None)
    if callable(method):
        return method()
    return getattr(component, "direct_feedthrough", None) or {}


def feedthrough_from_model_description(model_description: Any) -> dict[str, set[str]]:
    """The feedthrough map of an FMU from its fmpy ModelDescription.

    Each output depends on the inputs among its ModelStructure dependencies. FMI 2.0 says an
    ``<Unknown>`` without a ``dependencies`` attribute depends on everything, so it reads all
    inputs; an output missing from ModelStructure is treated the same way, to stay on the safe
    side (a loop solved needlessly costs time, a loop missed gives wrong results).
    """
    variables = model_description.modelVariables
    inputs = {v.name for v in variables if v.causality == "input"}
    declared: dict[str, set[str]] = {}
    for unknown in model_description.outputs:
        dependencies = unknown.dependencies
        declared[unknown.variable.name] = (
            set(inputs)
            if dependencies is None
            else {v.name for v in dependencies if v.name in inputs}
        )
    return {
        v.name: declared.get(v.name, set(inputs)) for v in variables if v.causality == "output"
    }


def _zero_delay_edges(
    components: Mapping[str, FeedthroughMap], connections: Sequence[ConnectionKey]
) -> dict[tuple[str, str], list[ConnectionKey]]:
    connected_outputs = {(src, port) for src, port, _, _ in connections}
    edges: dict[tuple[str, str], list[ConnectionKey]] = {}
    for connection in connections:
        src, _, dst, dst_port = connection
        zero_delay = any(
            dst_port in inputs and (dst, output) in connected_outputs
            for output, inputs in components[dst].items()
        )
        if zero_delay:
            edges.setdefault((src, dst), []).append(connection)
    return edges


def _generations(
    zero_delay: Mapping[tuple[str, str], list[ConnectionKey]], sccs: list[list[str]],
    connections: Sequence[ConnectionKey]
) -> list[list[str]]:
    """Topological generations of the condensation, each ordered so that a consumer runs before
    its delayed producer, and otherwise in the order the components were added (``sccs`` is
    sorted that way, so an SCC's index is its rank)."""
    scc_of = {name: index for index, scc in enumerate(sccs) for name in scc}
    condensed: dict[int, set[int]] = {}
    for src, dst in zero_delay:
        if scc_of[src] != scc_of[dst]:
            condensed.setdefault(scc_of[src], set()).add(scc_of[dst])
    generations = [sorted(generation)
                   for generation in topological_generations(len(sccs), condensed)]
    generation_of = {scc_id: index for index, generation in enumerate(generations)
                     for scc_id in generation}
    # (consumer, producer) of the delayed connections inside each generation, in the given order
    consumers_first: list[list[tuple[int, int]]] = [[] for _ in generations]
    for src, _, dst, _ in connections:
        producer, consumer = scc_of[src], scc_of[dst]
        if producer != consumer and generation_of[producer] == generation_of[consumer]:
            consumers_first[generation_of[producer]].append((consumer, producer))
    ordered = []
    for generation, edges in zip(generations, consumers_first, strict=True):
        if edges:
            generation = lexicographic_order(generation, _without_cycles(edges))
        ordered.append([name for scc_id in generation for name in sccs[scc_id]])
    return ordered


def _without_cycles(edges: list[tuple[int, int]]) -> dict[int, list[int]]:
    """The successors of `edges`, each edge left out that would close a cycle with the edges
    before it (so in a cycle the edge given first decides)."""
    everything: dict[int, list[int]] = {}
    for consumer, producer in edges:
        everything.setdefault(consumer, []).append(producer)
    # an edge between two strongly connected components of all the edges closes no cycle: only
    # the edges inside one need the search
    component_of = {node: index for index, component in
                    enumerate(strongly_connected(list(everything), everything))
                    for node in component}
    kept: dict[int, list[int]] = {}
    for consumer, producer in edges:
        if component_of[consumer] != component_of[producer] \
                or not reaches(kept, producer, consumer):
            kept.setdefault(consumer, []).append(producer)
    return kept


def _format_connection(connection: ConnectionKey) -> str:
    src, src_port, dst, dst_port = connection
    return f"{src}.{src_port} -> {dst}.{dst_port}"
