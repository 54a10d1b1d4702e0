"""The default experiment of an SSP: start and stop time, and a fixed step size."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Experiment:
    """None where the SSP gives no value. `step_size` comes from a known tool annotation
    (the Open Simulation Platform's FixedStepAlgorithm baseStepSize)."""

    start_time: float | None = None
    stop_time: float | None = None
    step_size: float | None = None
