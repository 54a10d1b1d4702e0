"""The execution order of a large system is found in time linear in its size: the connections
are read a fixed number of times, however many generations the graph has, and a path search
runs only for delayed connections that close a cycle."""

from __future__ import annotations

import pytest
from syssimx.graph import analysis
from syssimx.graph.analysis import analyze

FEEDTHROUGH = {"y": {"u"}}
NO_FEEDTHROUGH: dict[str, set[str]] = {"y": set()}


class CountedConnections(list):
    """A connection list that counts how often it is read whole."""

    reads = 0

    def __iter__(self):
        self.reads += 1
        return super().__iter__()


def chain(length: int, feedthrough: dict[str, set[str]]) -> tuple[dict, CountedConnections]:
    components = {f"c{i}": feedthrough for i in range(length)}
    connections = CountedConnections(
        (f"c{i}", "y", f"c{i + 1}", "u") for i in range(length - 1))
    return components, connections


@pytest.fixture
def path_searches(monkeypatch: pytest.MonkeyPatch) -> list[tuple[int, int]]:
    searched: list[tuple[int, int]] = []
    reaches = analysis.reaches

    def counting(successors, source, target):
        searched.append((source, target))
        return reaches(successors, source, target)

    monkeypatch.setattr(analysis, "reaches", counting)
    return searched


def test_a_zero_delay_chain_reads_its_connections_as_often_whatever_its_length():
    reads = {}
    for length in (10, 100):
        components, connections = chain(length, FEEDTHROUGH)
        found = analyze(components, connections)
        # the last link is delayed (nobody reads the last output): the last two share one
        assert len(found.generations) == length - 1
        reads[length] = connections.reads
    assert reads[10] == reads[100]


def test_a_delayed_chain_is_ordered_consumers_first_without_a_path_search(path_searches):
    components, connections = chain(100, NO_FEEDTHROUGH)
    assert analyze(components, connections).generations == [
        [f"c{i}" for i in reversed(range(100))]]
    assert path_searches == []


def test_only_the_connections_inside_a_delayed_cycle_search_and_the_first_given_decides(
        path_searches):
    # d -> a -> b -> c -> a, all delayed: the cycle's connections given first (a -> b, then
    # b -> c) put their consumers first; c -> a would close the cycle and is left out
    components = dict.fromkeys("dabc", NO_FEEDTHROUGH)
    connections = [("d", "y", "a", "u"), ("a", "y", "b", "u1"), ("b", "y", "c", "u"),
                   ("c", "y", "a", "u1")]
    assert analyze(components, connections).generations == [["c", "b", "a", "d"]]
    # searched from producer to consumer, by the order added: d 0, a 1, b 2, c 3
    assert sorted(path_searches) == [(1, 2), (2, 3), (3, 1)]
