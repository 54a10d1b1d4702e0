"""Error-controlled communication steps (the engine's ssx_set_step_control).

Every default is the engine's (ssx_get_defaults), and the engine judges the values."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ...bridge.options import engine_refusal
from ...engine import defaults, ffi, lib


@dataclass
class StepControl:
    """Chooses the communication steps inside each interval of the run's grid (dt) by the
    coupling error: the largest over the connections of |driver output at t + h - the input's
    value at t + h| / (atol + rtol |output|), the difference between what an input was given
    over the step and what its driver really reached.

    rollback=True: a step whose error exceeds 1 is taken again with a shorter step, from the
    state saved at its start (every component must support state rollback); rollback=False:
    the step is kept and only the next ones adapt (non-iterative, like libcosim's ECCO). The
    next step is the last times safety * error^(-1 / (input_order + 1)), at most 5 times
    longer, within [min_step, max_step] (max_step 0: bounded only by the grid interval);
    initial_step 0 starts with a tenth of the first grid interval times
    max(rtol, atol)^(1 / (input_order + 1))."""

    rtol: float = field(default_factory=lambda: defaults().step_rtol)
    atol: float = field(default_factory=lambda: defaults().step_atol)
    min_step: float = field(default_factory=lambda: defaults().step_min)
    max_step: float = 0.0
    initial_step: float = 0.0
    safety: float = field(default_factory=lambda: defaults().step_safety)
    rollback: bool = True

    def engine_struct(self) -> Any:
        return ffi.new("ssx_step_control *", {
            "enabled": 1, "rollback": int(bool(self.rollback)), "rtol": self.rtol,
            "atol": self.atol, "min_step": self.min_step, "max_step": self.max_step,
            "initial_step": self.initial_step, "safety": self.safety})

    def validate(self, owner: str) -> None:
        for name in ("rtol", "atol", "min_step", "max_step", "initial_step", "safety"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise ValueError(f"{owner}: step_control.{name} must be a number, got {value!r}")
        control = self.engine_struct()
        refusal = engine_refusal(lambda system: lib().ssx_set_step_control(system, control))
        if refusal is not None:
            raise ValueError(f"{owner}: {refusal}")
