"""Error-controlled communication steps (the engine's ssx_set_step_control).

Every default is the engine's (ssx_get_defaults), and the engine judges the values."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ...bridge.options import engine_refusal
from ...engine import defaults, ffi, lib
from ...errors import ConfigurationError


@dataclass
class StepControl:
    """Chooses the communication steps inside each interval of the run's grid (dt) by the
    coupling error: the largest over the connections of abs(driver output at t + h - the input's
    value at t + h) / (atol + rtol abs(output)), the difference between what an input was given
    over the step and what its driver really reached.

    rollback=True: a step whose error exceeds 1 is taken again with a shorter step, from the
    state saved at its start (every component must support state rollback); rollback=False:
    the step is kept and only the next ones adapt (non-iterative, like libcosim's ECCO). The
    next step is the last times safety * error^(-1 / (input_order + 1)), between min_change and
    max_change times the last, within [min_step, max_step] (max_step 0: bounded only by the grid
    interval); initial_step 0 starts with a tenth of the first grid interval times
    max(rtol, atol)^(1 / (input_order + 1)). min_step is at least the time resolution,
    2.2e-16 s (below it t + min_step == t near 1 s); where times are coarser, a step is at
    least two of their roundings.

    error="energy" measures, as libcosim's ECCO algorithm, the energy residual of the
    power_bonds instead: each bond is a pair of (component, input) ends, say a torque input
    and the velocity input of the other side, each driven by an output of the other side. Each
    side's power is its input times its output that drives the other end; the error is the
    root mean square over the bonds of abs(dP) h / (atol + rtol max(abs(P)) h), and the next
    step is the last times safety * error^-(integral_gain + proportional_gain) *
    previous_error^proportional_gain (a PI controller, Sadjina et al.).

    A step at min_step whose error still exceeds 1 is kept, counted in the statistics
    (steps_over_tolerance) and warned of once; strict=True makes it stop the run instead."""

    rtol: float = field(default_factory=lambda: defaults().step_rtol)
    atol: float = field(default_factory=lambda: defaults().step_atol)
    min_step: float = field(default_factory=lambda: defaults().step_min)
    max_step: float = 0.0
    initial_step: float = 0.0
    safety: float = field(default_factory=lambda: defaults().step_safety)
    rollback: bool = True
    min_change: float = field(default_factory=lambda: defaults().step_min_change)
    max_change: float = field(default_factory=lambda: defaults().step_max_change)
    error: str = "coupling"
    power_bonds: tuple[tuple[tuple[str, str], tuple[str, str]], ...] = ()
    proportional_gain: float = field(default_factory=lambda: defaults().step_proportional_gain)
    integral_gain: float = field(default_factory=lambda: defaults().step_integral_gain)
    strict: bool = False

    def __post_init__(self) -> None:
        # from YAML, lists: hashable and comparable as tuples
        if isinstance(self.power_bonds, list | tuple):
            self.power_bonds = tuple(
                tuple(tuple(end) if isinstance(end, list | tuple) else end for end in bond)
                if isinstance(bond, list | tuple) else bond for bond in self.power_bonds)

    def engine_struct(self) -> Any:
        return ffi.new("ssx_step_control *", {
            "enabled": 1, "rollback": int(bool(self.rollback)), "rtol": self.rtol,
            "atol": self.atol, "min_step": self.min_step, "max_step": self.max_step,
            "initial_step": self.initial_step, "safety": self.safety,
            "min_change": self.min_change, "max_change": self.max_change,
            "energy": int(self.error == "energy"), "proportional_gain": self.proportional_gain,
            "integral_gain": self.integral_gain, "strict": int(bool(self.strict))})

    def validate(self, owner: str) -> None:
        for flag in ("rollback", "strict"):
            if not isinstance(getattr(self, flag), bool):
                raise ConfigurationError(f"{owner}: step_control.{flag} must be true or false, "
                                         f"got {getattr(self, flag)!r}")
        if self.error not in ("coupling", "energy"):
            raise ConfigurationError(f"{owner}: step_control.error must be 'coupling' or "
                                     f"'energy', got {self.error!r}")
        if not isinstance(self.power_bonds, tuple):
            raise ConfigurationError(f"{owner}: step_control.power_bonds must be a list of "
                                     f"bonds, got {self.power_bonds!r}")
        for bond in self.power_bonds:
            if not (isinstance(bond, tuple) and len(bond) == 2 and all(
                    isinstance(end, tuple) and len(end) == 2 and
                    all(isinstance(name, str) for name in end) for end in bond)):
                raise ConfigurationError(f"{owner}: step_control.power_bonds: each bond is "
                                         f"two (component, input) ends, got {bond!r}")
        if self.error == "energy" and not self.power_bonds:
            raise ConfigurationError(f"{owner}: step_control.error 'energy' needs power_bonds")
        for name in ("rtol", "atol", "min_step", "max_step", "initial_step", "safety",
                     "min_change", "max_change", "proportional_gain", "integral_gain"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise ConfigurationError(f"{owner}: step_control.{name} must be a number, "
                                         f"got {value!r}")
        control = self.engine_struct()
        refusal = engine_refusal(lambda system: lib().ssx_set_step_control(system, control))
        if refusal is not None:
            raise ConfigurationError(f"{owner}: {refusal}")
