"""The default experiment of an SSP or OSP file: start and stop time, and a fixed step size."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Experiment:
    """None where the file gives no value. In an SSP `step_size` comes from a known tool
    annotation (the Open Simulation Platform's FixedStepAlgorithm baseStepSize, OMSimulator's
    FixedStepMaster stepSize); in an OSP system structure it is the BaseStepSize."""

    start_time: float | None = None
    stop_time: float | None = None
    step_size: float | None = None
