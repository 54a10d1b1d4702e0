"""The directed-graph algorithms the analysis needs, each linear in nodes plus edges.

A graph is its nodes and a mapping node -> successors. Written here rather than taken from
networkx, whose import alone costs more than running a small system.
"""

from __future__ import annotations

import heapq
from collections.abc import Hashable, Iterable, Mapping
from typing import TypeVar

Node = TypeVar("Node", bound=Hashable)
Successors = Mapping[Node, Iterable[Node]]


def strongly_connected(nodes: Iterable[Node], successors: Successors[Node]) -> list[list[Node]]:
    """The strongly connected components (Tarjan's algorithm, without recursion), each a
    component's nodes; every node is in exactly one."""
    index: dict[Node, int] = {}
    low: dict[Node, int] = {}
    stack: list[Node] = []
    on_stack: set[Node] = set()
    components: list[list[Node]] = []
    for root in nodes:
        if root in index:
            continue
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        work = [(root, iter(successors.get(root, ())))]
        while work:
            node, children = work[-1]
            for child in children:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(successors.get(child, ()))))
                    break
                if child in on_stack:
                    low[node] = min(low[node], index[child])
            else:  # every child seen: node is done
                work.pop()
                if work:
                    parent = work[-1][0]
                    low[parent] = min(low[parent], low[node])
                if low[node] == index[node]:
                    component = []
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        component.append(member)
                        if member == node:
                            break
                    components.append(component)
    return components


def generations(count: int, successors: Mapping[int, Iterable[int]]) -> list[list[int]]:
    """The topological generations of the acyclic graph of nodes 0..count-1: the nodes without
    predecessors, then those whose predecessors are all in earlier generations, and so on."""
    indegree = [0] * count
    for node in range(count):
        for child in successors.get(node, ()):
            indegree[child] += 1
    current = [node for node in range(count) if indegree[node] == 0]
    found = []
    while current:
        found.append(current)
        following = []
        for node in current:
            for child in successors.get(node, ()):
                indegree[child] -= 1
                if indegree[child] == 0:
                    following.append(child)
        current = following
    return found


def lexicographic_order(nodes: Iterable[int], successors: Mapping[int, Iterable[int]]
                        ) -> list[int]:
    """A topological order of the acyclic graph that takes the smallest node ready each time."""
    nodes = list(nodes)
    indegree = dict.fromkeys(nodes, 0)
    for node in nodes:
        for child in successors.get(node, ()):
            indegree[child] += 1
    ready = [node for node in nodes if indegree[node] == 0]
    heapq.heapify(ready)
    order = []
    while ready:
        node = heapq.heappop(ready)
        order.append(node)
        for child in successors.get(node, ()):
            indegree[child] -= 1
            if indegree[child] == 0:
                heapq.heappush(ready, child)
    return order


def reaches(successors: Successors[Node], source: Node, target: Node) -> bool:
    """Whether a path leads from source to target (a node reaches itself)."""
    seen = {source}
    pending = [source]
    while pending:
        node = pending.pop()
        if node == target:
            return True
        for child in successors.get(node, ()):
            if child not in seen:
                seen.add(child)
                pending.append(child)
    return False
