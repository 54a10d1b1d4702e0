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
        delayed_connections: zero-delay connections that close a cycle of components without a
            cycle of variables; they carry the value of the start of the step.
        undeclared_dependencies: what outputs without declared dependencies were taken to
            depend on ("all" inputs or "none").
        undeclared_in_loops: the components with outputs whose dependencies they do not
            declare and that form a loop only by the standard's assumption (every input).
    """

    components: list[str]
    zero_delay: dict[tuple[str, str], list[ConnectionKey]]
    generations: list[list[str]]
    loops: list[list[str]]
    order: list[str]
    loop_connections: list[ConnectionKey]
    delayed_connections: list[ConnectionKey]
    undeclared_dependencies: str
    undeclared_in_loops: list[str]

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
    components: Mapping[str, FeedthroughMap], connections: Sequence[ConnectionKey],
    undeclared: Mapping[str, set[str]] | None = None, undeclared_dependencies: str = "all"
) -> SystemAnalysis:
    """Analyze a system given as feedthrough maps per component and its data connections.

    Loops are found per variable: a cycle of connections and feedthrough dependencies through
    the ports. Components that drive one another without such a cycle (one's output depends on
    the other's, but not back on the same path) are no loop; they are ordered so that the
    outputs that depend on no input of the cycle are produced first, and the connection that
    would close the cycle carries its value of the start of the step.

    Args:
        components: component name -> {output port: input ports it depends on without delay},
            in the order the components were added (the tie-break of the execution order).
        connections: (src_comp, src_port, dst_comp, dst_port) for every data connection.
        undeclared: component name -> its outputs whose dependencies it does not declare (their
            feedthrough in ``components`` is the standard's assumption: every input).
        undeclared_dependencies: "all" takes that assumption (a loop it makes is solved), "none"
            takes such outputs to depend on no input (the loop is coupled explicitly, as
            libcosim couples every connection).

    Raises:
        ConfigurationError: (also a ValueError) a connection names a component that is not in
            ``components``, or ``undeclared_dependencies`` is neither "all" nor "none".
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
    check_undeclared_dependencies(undeclared_dependencies)
    undeclared = {name: set(outputs) for name, outputs in (undeclared or {}).items() if outputs}
    assumed_none = _without_undeclared(components, undeclared)
    effective = assumed_none if undeclared_dependencies == "none" else components

    loops_found = _variable_loops(names, effective, connections)
    loop_members = {name for loop in loops_found for name in loop}
    undeclared_in_loops: list[str] = []
    if undeclared:  # the loops that the standard's assumption makes (or would, under "none")
        without_assumption = {name for loop in _variable_loops(names, assumed_none, connections)
                              for name in loop}
        assumed = [loop for loop in _variable_loops(names, components, connections)
                   if not set(loop) <= without_assumption]
        undeclared_in_loops = [name for name in names if name in undeclared
                               and any(name in loop for loop in assumed)]

    zero_delay = _zero_delay_edges(effective, connections)
    for name in names:  # a component feeding itself is a loop only through a variable cycle
        if name not in loop_members:
            zero_delay.pop((name, name), None)
    added = {name: i for i, name in enumerate(names)}
    unit_of = {name: index for index, loop in enumerate(loops_found) for name in loop}
    units = [list(loop) for loop in loops_found]
    for name in names:
        if name not in unit_of:
            unit_of[name] = len(units)
            units.append([name])
    delayed = _order_cycles_without_loops(
        effective, connections, zero_delay, unit_of, [added[u[0]] for u in units])
    for edge in delayed:
        del zero_delay[edge]
    sccs = sorted((sorted(unit, key=added.__getitem__) for unit in units),
                  key=lambda members: added[members[0]])
    loops = [scc for scc in sccs if scc[0] in loop_members]
    generations = _generations(zero_delay, sccs, connections)
    order = [name for generation in generations for name in generation]
    position = {name: index for index, name in enumerate(order)}
    loops.sort(key=lambda loop: position[loop[0]])

    loop_index = {name: index for index, loop in enumerate(loops) for name in loop}
    loop_connections = [
        connection
        for (src, dst), behind in zero_delay.items()
        if src in loop_index and loop_index[src] == loop_index.get(dst)
        for connection in behind
    ]
    given_order = {connection: i for i, connection in enumerate(connections)}
    loop_connections.sort(key=given_order.__getitem__)
    delayed_connections = sorted((c for edge in delayed.values() for c in edge),
                                 key=given_order.__getitem__)
    return SystemAnalysis(names, zero_delay, generations, loops, order, loop_connections,
                          delayed_connections, undeclared_dependencies, undeclared_in_loops)


UNDECLARED_DEPENDENCIES = ("all", "none")
"""What an output whose dependencies its FMU does not declare depends on: every input (the
standard's assumption: a loop it makes is solved) or none (coupled explicitly, as libcosim
does)."""


def check_undeclared_dependencies(value: Any) -> str:
    """``value`` when it is one of UNDECLARED_DEPENDENCIES, else a ConfigurationError."""
    if value not in UNDECLARED_DEPENDENCIES:
        raise ConfigurationError(f"undeclared_dependencies must be 'all' (the standard: solve "
                                 f"the loops it makes) or 'none' (couple them explicitly), "
                                 f"not {value!r}")
    return str(value)


def _without_undeclared(components: Mapping[str, FeedthroughMap],
                        undeclared: Mapping[str, set[str]]) -> dict[str, FeedthroughMap]:
    return {name: {output: set() if output in undeclared.get(name, ()) else set(inputs)
                   for output, inputs in feedthrough.items()}
            for name, feedthrough in components.items()}


Port = tuple[str, str, str]
"""("in" or "out", component, port)"""


def _port_graph(components: Mapping[str, FeedthroughMap], connections: Sequence[ConnectionKey]
                ) -> dict[Port, list[Port]]:
    """Successors per port: a connection leads from an output to an input, a feedthrough
    dependency from an input to a connected output of the same component."""
    connected = {(src, port) for src, port, _, _ in connections}
    successors: dict[Port, list[Port]] = {}
    for src, src_port, dst, dst_port in connections:
        successors.setdefault(("out", src, src_port), []).append(("in", dst, dst_port))
    for name, feedthrough in components.items():
        for output, inputs in feedthrough.items():
            if (name, output) in connected:
                for port in inputs:
                    successors.setdefault(("in", name, port), []).append(("out", name, output))
    return successors


def _variable_loops(names: list[str], components: Mapping[str, FeedthroughMap],
                    connections: Sequence[ConnectionKey]) -> list[list[str]]:
    """The components of each cycle through ports; cycles that share a component are one
    loop (the engine solves a loop as a group of components). In the order added."""
    successors = _port_graph(components, connections)
    parent = {name: name for name in names}

    def root(name: str) -> str:
        while parent[name] != name:
            parent[name] = parent[parent[name]]
            name = parent[name]
        return name

    in_loop: set[str] = set()
    for scc in strongly_connected(list(successors), successors):
        if len(scc) > 1:
            members = {port[1] for port in scc}
            in_loop |= members
            first = root(next(iter(members)))
            for member in members:
                parent[root(member)] = first
    groups: dict[str, list[str]] = {}
    for name in names:
        if name in in_loop:
            groups.setdefault(root(name), []).append(name)
    return list(groups.values())


def _order_cycles_without_loops(
    components: Mapping[str, FeedthroughMap], connections: Sequence[ConnectionKey],
    zero_delay: Mapping[tuple[str, str], list[ConnectionKey]], unit_of: Mapping[str, int],
    added: list[int]
) -> dict[tuple[str, str], list[ConnectionKey]]:
    """The zero-delay edges to delay so that the units (a loop or a single component) form
    no cycle. Such a cycle has no cycle through ports (that would be a loop): inside it, a
    unit ranks by the earliest of its outputs in the ports' dependency order, ties by the
    order added, and an edge from a later unit to an earlier one is delayed."""
    unit_successors: dict[int, set[int]] = {}
    for src, dst in zero_delay:
        if unit_of[src] != unit_of[dst]:
            unit_successors.setdefault(unit_of[src], set()).add(unit_of[dst])
    cycle_of = {unit: index for index, scc in enumerate(
        strongly_connected(sorted(set(unit_of.values())), unit_successors)) if len(scc) > 1
        for unit in scc}
    if not cycle_of:
        return {}
    depth = _port_depths(components, connections)
    rank: dict[int, tuple[int, int]] = {}
    for (src, dst), behind in zero_delay.items():
        unit = unit_of[src]
        if unit in cycle_of and cycle_of[unit] == cycle_of.get(unit_of[dst]):
            earliest = min(depth[("out", c[0], c[1])] for c in behind)
            rank[unit] = min(rank.get(unit, (earliest, added[unit])), (earliest, added[unit]))
    delayed = {}
    for (src, dst), behind in zero_delay.items():
        a, b = unit_of[src], unit_of[dst]
        if a != b and a in cycle_of and cycle_of[a] == cycle_of.get(b) \
                and rank.get(a, (0, added[a])) > rank.get(b, (0, added[b])):
            delayed[src, dst] = behind
    return delayed


def _port_depths(components: Mapping[str, FeedthroughMap],
                 connections: Sequence[ConnectionKey]) -> dict[Port, int]:
    """The longest chain of dependencies that leads to each port (ports of one cycle share
    theirs)."""
    successors = _port_graph(components, connections)
    depth: dict[Port, int] = {}
    # Tarjan lists a component after every component it reaches: reversed, sources come first
    for scc in reversed(strongly_connected(list(successors), successors)):
        level = max((depth.get(port, 0) for port in scc), default=0)
        for port in scc:
            depth[port] = level
        for port in scc:
            for child in successors.get(port, ()):
                if child not in scc:
                    depth[child] = max(depth.get(child, 0), level + 1)
    return depth


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
    undeclared = {name: _undeclared_of(component)
                  for name, component in system.components.items()}
    return analyze(components, connections, undeclared,
                   getattr(system, "undeclared_dependencies", "all"))


def _undeclared_of(component: Any) -> set[str]:
    method = getattr(component, "undeclared_outputs", None)
    return method() if callable(method) else set()


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


def undeclared_outputs(model_description: Any) -> set[str]:
    """The outputs of an FMU (fmpy ModelDescription) whose dependencies it does not declare:
    ModelStructure lists them without ``dependencies``, or not at all."""
    declared = {unknown.variable.name for unknown in model_description.outputs
                if unknown.dependencies is not None}
    return {v.name for v in model_description.modelVariables
            if v.causality == "output" and v.name not in declared}


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
