"""Observers of a run on the Python side: a user's object called at every sample the history
keeps (ssx_add_observer), and block writers handed the samples in blocks (ssx_add_block_observer)
so that a file is written while the run goes on. Both see exactly the samples of the history.

A sample's values are every component's outputs, in component order and each component's
output order: the names `columns(plan)` gives ("Pendulum.theta").
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

import numpy as np

from ..engine import ffi, lib
from .deferred_interrupt import interrupts_deferred
from .plan import CallbackFailure, EnginePlan

# A block a writer is handed holds about this many bytes (time, micro and the values): large
# enough that a file format's cost per block (a Parquet row group and its footer entry) is
# paid rarely, small enough that memory stays a few blocks.
BLOCK_BYTES = 8 << 20

BlockWriter = Callable[[np.ndarray, np.ndarray, np.ndarray], None]


def columns(plan: EnginePlan) -> list[str]:
    """The names of a sample's values: component.output, in the engine's order."""
    return [f"{name}.{output}" for name in plan.index for output in plan.outputs[name]]


def _output_views(plan: EnginePlan) -> list[np.ndarray]:
    """Each component's engine outputs as an array that follows them (never copied)."""
    views = []
    for name, index in plan.index.items():
        n = len(plan.outputs[name])
        if n > 0:
            pointer = lib().ssx_outputs(plan.sys, index)
            views.append(np.frombuffer(ffi.buffer(pointer, n * 8), dtype=np.float64))
    return views


def _no_values() -> np.ndarray:
    return np.empty(0)


def _event_source(plan: EnginePlan, record: Any) -> tuple[str, str]:
    """(component, event) of an event record: an indicator's, or a component's own event."""
    if record.indicator >= 0:
        return plan.indicators[record.indicator]
    return (list(plan.index)[record.component],
            plan.own_event_name(record.component, record.own, record.clock))


def add_observer(plan: EnginePlan, observer: Any) -> int:
    """Calls observer.step_complete(t, micro, values) at every sample (values: a new array of
    the sample's values, named by columns(plan)), and, where the observer has them,
    start(t0, columns), state_restored(t), event(t, micro, component, event) and run_end().
    An exception in one stops the run and is raised by it. Returns the engine's id."""
    names = columns(plan)
    step_complete = observer.step_complete
    # a new array per sample: one component's outputs copied, several concatenated; over the
    # outputs where they are (initialize may move them: taken again at each start)
    values: Callable[[], np.ndarray] = _no_values

    def take_views() -> None:
        nonlocal values
        views = _output_views(plan)
        values = (views[0].copy if len(views) == 1 else
                  functools.partial(np.concatenate, views) if views else _no_values)

    def failed(where: str) -> Callable[[BaseException], None]:
        def keep(exc: BaseException) -> None:
            if plan.failure is None:
                plan.failure = CallbackFailure(type(observer).__name__, f"observer {where}",
                                               float(lib().ssx_time(plan.sys)), exc)
        return keep

    def on_step(_user: Any, t: float, micro: int) -> int:
        step_complete(t, micro, values())
        return 0

    callbacks = ffi.new("ssx_observer_callbacks *")
    callbacks.step_complete = plan.callback("int(void *, double, int)", on_step, -1,
                                            failed("step_complete"))
    def on_start(_user: Any, t0: float) -> int:
        take_views()
        if hasattr(observer, "start"):
            observer.start(t0, names)
        return 0
    callbacks.start = plan.callback("int(void *, double)", on_start, -1, failed("start"))
    if hasattr(observer, "state_restored"):
        def on_restored(_user: Any, t: float) -> int:
            observer.state_restored(t)
            return 0
        callbacks.state_restored = plan.callback("int(void *, double)", on_restored, -1,
                                                 failed("state_restored"))
    if hasattr(observer, "event"):
        def on_event(_user: Any, record: Any) -> int:
            component, event = _event_source(plan, record)
            observer.event(float(record.t), int(record.micro), component, event)
            return 0
        callbacks.event = plan.callback("int(void *, ssx_event_record *)", on_event, -1,
                                        failed("event"))
    if hasattr(observer, "run_end"):
        def on_run_end(_user: Any) -> int:
            observer.run_end()
            return 0
        callbacks.run_end = plan.callback("int(void *)", on_run_end, -1, failed("run_end"))
    return plan.check(lib().ssx_add_observer(plan.sys, callbacks, ffi.NULL), "add_observer")


def add_block_writer(plan: EnginePlan, write: BlockWriter, rows: int | None = None) -> int:
    """Calls write(t, micro, values) with each block of samples (values: n_rows x n_columns,
    named by columns(plan); rows: a block's, by default about BLOCK_BYTES); the arrays are
    valid only during the call. Returns the id."""
    if rows is None:
        rows = max(1, BLOCK_BYTES // (12 + 8 * len(columns(plan))))
    def on_block(_user: Any, t: Any, micro: Any, values: Any, n_rows: int,
                 n_columns: int) -> int:
        # Ctrl-C before the block is begun: -1, and the engine hands it again as the run ends;
        # once written, 1: the run stops with the block written once
        written = False
        try:
            with interrupts_deferred():
                write(np.frombuffer(ffi.buffer(t, n_rows * 8), dtype=np.float64),
                      np.frombuffer(ffi.buffer(micro, n_rows * 4), dtype=np.int32),
                      np.frombuffer(ffi.buffer(values, n_rows * n_columns * 8),
                                    dtype=np.float64).reshape(n_rows, n_columns))
                written = True
        except BaseException as exc:
            if not written:
                raise
            keep(exc)
            return 1
        return 0

    def keep(exc: BaseException) -> None:
        if plan.failure is None:
            plan.failure = CallbackFailure(plan.name, "stream writer",
                                           float(lib().ssx_time(plan.sys)), exc)

    callback = plan.callback("ssx_block_writer", on_block, -1, keep)
    return plan.check(lib().ssx_add_block_observer(plan.sys, rows, callback, ffi.NULL),
                      "add_block_observer")


def remove_observer(plan: EnginePlan, observer_id: int) -> None:
    plan.check(lib().ssx_remove_observer(plan.sys, observer_id), "remove_observer")


def keep_history(plan: EnginePlan, keep: bool) -> None:
    plan.check(lib().ssx_set_history(plan.sys, int(keep)), "history")
