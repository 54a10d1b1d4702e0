"""Ctrl-C in a streamed run (issue 34, item 3): the file holds every sample recorded up to the
interruption, exactly those partial_result holds; with keep_history=False, the file still
holds them all and the interrupt says that partial_result holds none."""

from __future__ import annotations

import csv
import os
import signal
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest
from syssimx import FMUComponent, System, fmus
from syssimx.bridge import observers
from syssimx.errors import RunInterrupted
from syssimx.streaming.csv_writer import CsvWriter

ROWS_PER_BLOCK = 1000
INTERRUPTED_BLOCK = 3  # the writer's calls: the start point, then blocks


@pytest.fixture
def small_blocks(monkeypatch: pytest.MonkeyPatch) -> None:
    columns = 3  # the pendulum's outputs
    monkeypatch.setattr(observers, "BLOCK_BYTES", ROWS_PER_BLOCK * (12 + 8 * columns))


def pendulum() -> System:
    system = System("s")
    system.add_component(FMUComponent("P", fmus.path("pendulum_euler")))
    system.initialize(0.0)
    return system


def streamed(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """The file's times and micro steps."""
    with path.open() as stream:
        rows = list(csv.reader(stream))
    assert rows[0][:2] == ["time", "micro"]
    return (np.array([float(row[0]) for row in rows[1:]]),
            np.array([int(row[1]) for row in rows[1:]]))


def interrupt_inside_a_block(monkeypatch: pytest.MonkeyPatch) -> None:
    """Ctrl-C arrives while the writer writes its third call's block, half of it written."""
    calls = 0
    write = CsvWriter.write

    def write_interrupted(self: CsvWriter, t: np.ndarray, micro: np.ndarray,
                          values: np.ndarray) -> None:
        nonlocal calls
        calls += 1
        if calls != INTERRUPTED_BLOCK:
            write(self, t, micro, values)
            return
        half = len(t) // 2
        write(self, t[:half], micro[:half], values[:half])
        os.kill(os.getpid(), signal.SIGINT)
        write(self, t[half:], micro[half:], values[half:])

    monkeypatch.setattr(CsvWriter, "write", write_interrupted)


@pytest.mark.usefixtures("small_blocks")
def test_ctrl_c_inside_a_block_keeps_the_file_and_the_partial_result_equal(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    """Before: the file ended at the block before, the partial result held the samples of the
    block the interrupt fell in too."""
    interrupt_inside_a_block(monkeypatch)
    path = tmp_path / "run.csv"
    with pytest.raises(RunInterrupted) as caught:
        pendulum().run(0.0, 100.0, 1e-3, stream_to=path)
    t, _ = caught.value.partial_result["P"]
    t_file, _ = streamed(path)
    assert len(t) >= (INTERRUPTED_BLOCK - 1) * ROWS_PER_BLOCK
    np.testing.assert_array_equal(t_file, t)


@pytest.mark.usefixtures("small_blocks")
def test_ctrl_c_before_a_block_is_begun_loses_none_of_it(tmp_path: Path,
                                                         monkeypatch: pytest.MonkeyPatch):
    """Ctrl-C on the block writer's first line, before the interrupt can be held back: the
    engine hands the block again as the run ends. Before: the block was lost."""
    calls = 0
    deferred = observers.interrupts_deferred

    @contextmanager
    def interrupted_on_entry() -> Iterator[None]:
        nonlocal calls
        calls += 1
        if calls == INTERRUPTED_BLOCK:
            raise KeyboardInterrupt
        with deferred():
            yield

    monkeypatch.setattr(observers, "interrupts_deferred", interrupted_on_entry)
    path = tmp_path / "run.csv"
    with pytest.raises(RunInterrupted) as caught:
        pendulum().run(0.0, 100.0, 1e-3, stream_to=path)
    t, _ = caught.value.partial_result["P"]
    t_file, _ = streamed(path)
    assert len(t) >= (INTERRUPTED_BLOCK - 1) * ROWS_PER_BLOCK
    np.testing.assert_array_equal(t_file, t)


@pytest.mark.usefixtures("small_blocks")
def test_ctrl_c_without_history_keeps_every_sample_in_the_file(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    """keep_history=False: the file holds every step up to the time the run reached, and the
    interrupt says that partial_result holds no samples (before: it said it held them all,
    and the file lacked the last block)."""
    interrupt_inside_a_block(monkeypatch)
    path = tmp_path / "run.csv"
    with pytest.raises(RunInterrupted, match="partial_result holds no samples; they are all "
                       "in") as caught:
        pendulum().run(0.0, 100.0, 1e-3, stream_to=path, keep_history=False)
    reached = caught.value.partial_result.tf
    t_file, _ = streamed(path)
    steps = round(reached / 1e-3)
    assert steps >= (INTERRUPTED_BLOCK - 1) * ROWS_PER_BLOCK
    np.testing.assert_allclose(t_file, np.arange(steps + 1) * 1e-3, rtol=0, atol=1e-9)


def test_ctrl_c_held_back_reaches_the_handler_in_place_once_the_block_is_done():
    from syssimx.bridge.deferred_interrupt import interrupts_deferred

    received: list[int] = []
    previous = signal.signal(signal.SIGINT, lambda number, _frame: received.append(number))
    try:
        with interrupts_deferred():
            os.kill(os.getpid(), signal.SIGINT)
            assert received == []
        assert received == [signal.SIGINT]
    finally:
        signal.signal(signal.SIGINT, previous)
