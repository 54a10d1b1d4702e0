"""How an ensemble's members are cut into Dask tasks, and how a task's results travel as one
block (no cluster needed)."""

from __future__ import annotations

import numpy as np
import pendulum_wall
from syssimx.ensemble import MemberResult, MemberTask
from syssimx.ensemble.block import pack, run_block
from syssimx.ensemble.member import run_member
from syssimx.ensemble.runner import AHEAD, MAX_CHUNK, TASK_SECONDS, announcing, next_size


def tasks(count: int) -> list[MemberTask]:
    return [MemberTask(index, {"P.theta0": 0.1}, 0.0, 1.0, 0.1) for index in range(count)]


def test_tasks_are_sized_from_the_measured_member_time() -> None:
    assert next_size(2000, 2, None) == 1  # the first tasks measure
    assert next_size(2000, 2, TASK_SECONDS / 20) == 20
    assert next_size(2000, 2, 1e-6) == MAX_CHUNK
    assert next_size(2000, 2, 1.0) == 1  # a long member is a task of its own
    # the last tasks are small, so that no worker is left with a long one alone
    assert next_size(30, 2, TASK_SECONDS / 20) == -(-30 // (AHEAD * 2))
    assert next_size(1, 2, TASK_SECONDS / 20) == 1


def test_only_a_chunks_first_member_announces_its_start_unless_the_watchdog_times_each() -> None:
    assert [task.topic for task in announcing(tasks(4), "topic", every_member=False)] == \
        ["topic", None, None, None]
    assert [task.topic for task in announcing(tasks(4), "topic", every_member=True)] == \
        ["topic"] * 4


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
