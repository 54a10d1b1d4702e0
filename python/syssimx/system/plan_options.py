"""The records of a system's algorithm and run settings in its plan: what System.initialize
gives the engine before it runs (its coupling, loops, threads, step control, the hybrid
algorithm's options, the non-finite and output interval settings)."""

from __future__ import annotations

from ..engine import defaults, ffi
from ..plan.records import PlanRecords, Word
from .algorithms import Algorithm, HybridAlgorithm, StepControl


def option_records(algorithm: Algorithm, power_bond_ends: list[int]) -> PlanRecords:
    """The records of `algorithm` (validated), in the order the engine takes them;
    power_bond_ends: the engine's (component, input) of the step control's bonds, four a
    bond."""
    records = PlanRecords()
    coupling = algorithm.coupling if isinstance(algorithm, HybridAlgorithm) else algorithm
    records.add("coupling", Word(coupling.engine_coupling.removeprefix("SSX_").lower()),
                about="coupling")
    records.add("loop_options", float(coupling.tolerance), int(coupling.max_iter),
                float(coupling.damping), about="loop options")
    records.add("loop_jacobian", Word(coupling.loop_jacobian), about="loop Jacobian")
    records.add("threads", int(coupling.threads), about="threads")
    records.add("input_order", int(coupling.input_order), about="input order")
    records.add("extrapolate_held_inputs", bool(coupling.extrapolate_held_inputs),
                about="held input extrapolation")
    records.add("step_control", *_step_control_fields(coupling.step_control),
                about="step control")
    records.add("power_bonds", [tuple(power_bond_ends[k:k + 4])
                                for k in range(0, len(power_bond_ends), 4)],
                about="power bonds")
    if isinstance(algorithm, HybridAlgorithm):
        records.add("hybrid_options", float(algorithm.tol_time), float(algorithm.tol_value),
                    int(algorithm.max_iter), int(algorithm.max_microsteps),
                    bool(algorithm.record_internal_steps), Word(algorithm.method),
                    float(algorithm.zeno_min_interval), about="hybrid options")
    return records


def _step_control_fields(control: StepControl | None) -> list[bool | float]:
    """The fields of the engine's ssx_step_control in order (none: switched off), its int
    fields as flags."""
    struct = control.engine_struct() if control is not None \
        else ffi.new("ssx_step_control *", {"enabled": 0})
    return [bool(value) if isinstance(value, int) else float(value)
            for name, _ in ffi.typeof("ssx_step_control").fields
            for value in (getattr(struct, name),)]


def setting_records(settings: tuple[int, int | None]) -> PlanRecords:
    """The records of System.initialize's (allow_non_finite, output_interval)."""
    records = PlanRecords()
    records.add("allow_non_finite", bool(settings[0]), about="allow_non_finite")
    records.add("output_interval", defaults().output_interval if settings[1] is None
                else settings[1], about="output_interval")
    return records
