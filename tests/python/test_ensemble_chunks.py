"""How an ensemble's members are cut into Dask tasks, and how a task's results travel as one
block (no cluster needed)."""

from __future__ import annotations

import numpy as np
import pendulum_wall
from syssimx.ensemble import MemberResult, MemberTask
from syssimx.ensemble.block import pack, run_block
from syssimx.ensemble.member import run_member
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


def _seed() -> object:
    return pendulum_wall.build("euler")[0]


def test_a_block_gives_back_each_members_result_to_the_bit() -> None:
    """Three seed members in one block, one of them failing before it recorded anything:
    each MemberResult cut from the block equals the member run alone."""
    members = [MemberTask(0, {"P.theta0": 0.3}, 0.0, 1.0, 0.05, ensemble="block"),
               MemberTask(1, {"P.nothing": 1.0}, 0.0, 1.0, 0.05, ensemble="block"),
               MemberTask(2, {"P.theta0": 0.5}, 0.0, 1.0, 0.05, ensemble="block")]
    block = run_block(_seed, members)
    assert len(block) == 3 and len(block.others) == 1  # the failed member travels alone
    got = {r.index: r for r in block.results({t.index: t.parameters for t in members})}
    for task in members:
        alone: MemberResult = run_member(_seed, task)
        mine = got[task.index]
        assert (mine.status, mine.error_type, mine.events, mine.statistics,
                mine.termination, mine.parameters) == \
            (alone.status, alone.error_type, alone.events, alone.statistics,
             alone.termination, task.parameters)
        assert np.array_equal(mine.time, alone.time) and np.array_equal(mine.micro, alone.micro)
        assert mine.outputs.keys() == alone.outputs.keys()
        for name, series in alone.outputs.items():
            assert np.array_equal(mine.outputs[name], series)
    assert got[1].status == "failed" and "nothing" in got[1].error
    assert got[0].events[0][0] != got[2].events[0][0]  # the block kept them apart


def test_an_empty_block() -> None:
    block = pack([])
    assert len(block) == 0 and block.results({}) == []
