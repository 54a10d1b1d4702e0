"""How an ensemble's members are cut into Dask tasks, and how a task's results travel as one
block (no cluster needed)."""

from __future__ import annotations

import numpy as np
import pendulum_wall
from syssimx.ensemble import MemberResult, MemberTask
from syssimx.ensemble.block import pack, run_block
from syssimx.ensemble.chunk import Experiment
from syssimx.ensemble.member import run_member
from syssimx.ensemble.runner import chunk_size, split

EXPERIMENT = Experiment(0.0, 1.0, 0.1)


def sets(count: int) -> list[dict[str, float]]:
    return [{"P.theta0": 0.1 * index} for index in range(count)]


def test_chunks_come_in_a_multiple_of_the_workers_and_differ_by_one_member_at_most() -> None:
    assert (chunk_size(200, 2), chunk_size(800, 2), chunk_size(8000, 2)) == (34, 134, 1024)
    assert len(split(sets(2000), chunk_size(2000, 2), 2, EXPERIMENT)) == 6  # 3 per worker
    # 13 chunks of 64 would leave one worker a chunk alone
    chunks = split(sets(800), 64, 2, EXPERIMENT)
    assert sorted(len(chunk) for chunk in chunks) == [57] * 12 + [58] * 2
    assert [task.index for chunk in chunks for task in chunk.tasks()] == list(range(800))
    assert [task.parameters for chunk in chunks for task in chunk.tasks()] == sets(800)
    assert [len(chunk) for chunk in split(sets(3), 1, 2, EXPERIMENT)] == [1, 1, 1]


def test_only_a_chunk_of_one_member_announces_its_start_unless_the_watchdog_times_each() -> None:
    chunks = split(sets(8), 4, 2, EXPERIMENT, "topic")
    assert [[task.topic for task in chunk.tasks()] for chunk in chunks] == [[None] * 4] * 2
    assert [[task.topic for task in chunk.tasks()] for chunk in split(sets(2), 1, 2, EXPERIMENT,
                                                                      "topic")] == [["topic"]] * 2
    watched = split(sets(8), 4, 2, EXPERIMENT, "topic", announce_each=True)
    assert all(task.topic == "topic" for chunk in watched for task in chunk.tasks())


def test_a_chunk_s_members_run_the_experiment() -> None:
    experiment = Experiment(0.5, 2.0, 0.25, ("P.theta",), 3.0, "ensemble")
    [chunk] = split(sets(3)[1:], 2, 1, experiment)
    assert chunk.tasks()[1] == MemberTask(1, {"P.theta0": 0.2}, 0.5, 2.0, 0.25, ("P.theta",),
                                          3.0, None, "ensemble")


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


def test_results_kept_as_blocks_give_the_dataset_of_the_members_run_alone() -> None:
    """A MemberList of two blocks and a loose member, one member already cut from its block:
    its dataset, failures and members are those of the same members run one by one."""
    import pytest

    pytest.importorskip("xarray")
    from syssimx.ensemble.member_list import MemberList
    from syssimx.ensemble.members import ParameterTable
    from syssimx.ensemble.result import EnsembleResult

    values = [{"P.theta0": 0.3}, {"P.theta0": "text"}, {"P.theta0": 0.5}, {"P.theta0": 0.4},
              {"P.theta0": 0.6}]
    experiment = Experiment(0.0, 1.0, 0.05, ensemble="blocks")
    tasks = [experiment.task(index, parameters) for index, parameters in enumerate(values)]
    kept = MemberList(ParameterTable.of(values))
    assert kept.add_block(run_block(_seed, tasks[:3])) == (3, 1)  # members, failed
    kept.add_block(run_block(_seed, tasks[4:]))
    kept.add(run_member(_seed, tasks[3]))
    assert kept[2].parameters == values[2]  # cut before the dataset is built
    alone = [run_member(_seed, task) for task in tasks]
    from_blocks = EnsembleResult(kept, ["P.theta0"], 0.0, 1.0, 0.05, 0.0)
    one_by_one = EnsembleResult(alone, ["P.theta0"], 0.0, 1.0, 0.05, 0.0)
    assert [m.index for m in from_blocks.failed] == [m.index for m in one_by_one.failed] == [1]
    ours, theirs = from_blocks.dataset, one_by_one.dataset
    assert ours.drop_vars(["wall_time", "worker"]).identical(
        theirs.drop_vars(["wall_time", "worker"]))
    assert np.array_equal(from_blocks.members[4].outputs["P.theta"],
                          one_by_one.members[4].outputs["P.theta"])
    grid = from_blocks.grid()  # every member at once, from the padded arrays
    assert grid.identical(one_by_one.grid())
    for member in alone:  # at each grid time, the first sample there (before an event)
        expected = [next((value for t, value in zip(member.time, member.outputs["P.theta"],
                                                       strict=True) if abs(t - g) < 1e-12),
                         np.nan) if member.time.size else np.nan
                    for g in grid["time"].values]
        np.testing.assert_array_equal(grid["P.theta"].values[member.index], expected)
    table = from_blocks.to_dataframe()  # from the padded arrays, no table per member
    assert table.equals(one_by_one.to_dataframe())
    for member in alone:  # each member's rows are its own samples, or one of NaN
        rows = table[table.member == member.index]
        assert list(rows.status.unique()) == [member.status]
        if member.time.size:
            assert np.array_equal(rows.time, member.time)
            assert np.array_equal(rows.micro, member.micro)
            assert np.array_equal(rows["P.omega"], member.outputs["P.omega"])
        else:
            assert len(rows) == 1 and np.isnan(rows.time.iloc[0])


def test_chunks_after_the_probe_are_sized_by_the_members_after_a_block_s_first() -> None:
    """A worker's first member builds the System and loads what it needs (2.5 s of pint for the
    seed scenario): sized by it, every later task would be one member long (the design tried
    before, which multiplied the client's CPU). A block's cost is its later members' CPU."""
    from syssimx.ensemble.runner import TASK_SECONDS, sized

    probe = run_block(_seed, [EXPERIMENT.task(index, {"P.theta0": 0.3}) for index in range(3)])
    alone = run_block(_seed, [EXPERIMENT.task(0, {"P.theta0": 0.3})])
    assert probe.cost is not None and 0 < probe.cost < 0.1 and alone.cost is None
    assert sized(1992, 2, 0.0025) == round(TASK_SECONDS / 0.0025) < chunk_size(1992, 2)
    assert sized(1992, 2, 0.00001) == chunk_size(1992, 2)  # chunk_size's bound kept
    assert sized(1992, 2, 1.0) == 1 and sized(1992, 2, None) == chunk_size(1992, 2)
    # the chunks after the probe continue its member indices
    chunks = split(sets(10)[4:], 3, 2, EXPERIMENT, first=4)
    assert [task.index for chunk in chunks for task in chunk.tasks()] == list(range(4, 10))
    assert chunks[0].parameters[0] == sets(10)[4]
