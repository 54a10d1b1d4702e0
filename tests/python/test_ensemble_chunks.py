"""How an ensemble's members are cut into Dask tasks (no cluster needed)."""

from __future__ import annotations

from syssimx.ensemble import MemberTask
from syssimx.ensemble.runner import chunk_size, split


def tasks(count: int) -> list[MemberTask]:
    return [MemberTask(index, {"P.theta0": 0.1}, 0.0, 1.0, 0.1) for index in range(count)]


def test_chunks_come_in_a_multiple_of_the_workers_and_differ_by_one_member_at_most() -> None:
    assert (chunk_size(200, 2), chunk_size(800, 2)) == (25, 64)
    # 13 chunks of 64 would leave one worker a chunk alone
    chunks = split(tasks(800), 64, 2, "topic", every_member=False)
    assert sorted(len(chunk) for chunk in chunks) == [57] * 12 + [58] * 2
    assert [task.index for chunk in chunks for task in chunk] == list(range(800))
    assert [len(chunk) for chunk in split(tasks(3), 1, 2, "topic", every_member=False)] == \
        [1, 1, 1]


def test_only_a_chunks_first_member_announces_its_start_unless_the_watchdog_times_each() -> None:
    chunks = split(tasks(8), 4, 2, "topic", every_member=False)
    assert [[task.topic for task in chunk] for chunk in chunks] == \
        [["topic", None, None, None]] * 2
    watched = split(tasks(8), 4, 2, "topic", every_member=True)
    assert all(task.topic == "topic" for chunk in watched for task in chunk)
