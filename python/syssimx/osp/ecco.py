"""libcosim's `ecco` algorithm as syssimx runs it: Jacobi with the communication step chosen by
the coupling error and no rollback (like ECCO, only the coming steps adapt), bounded by the
<EccoConfiguration>'s step sizes. ECCO's own error measure (the energy residual of the power
bonds, under a PI controller) is not syssimx's: the reader says so in one warning."""

from __future__ import annotations

from ..system.algorithms import JacobiAlgorithm, StepControl

# <EccoConfiguration> element -> StepControl field
_STEP_CONTROL_FIELDS = {"SafetyFactor": "safety", "StepSize": "initial_step",
                        "MinimumStepSize": "min_step", "MaximumStepSize": "max_step",
                        "RelativeTolerance": "rtol", "AbsoluteTolerance": "atol"}
# what ECCO's controller reads that syssimx's does not
IGNORED_ECCO_SETTINGS = ("ProportionalGain", "IntegralGain", "MinimumChangeRate",
                         "MaximumChangeRate", "PowerResidualTolerance")


def ecco_algorithm(config: dict[str, float]) -> JacobiAlgorithm:
    """The algorithm an <Algorithm>ecco</Algorithm> structure runs with."""
    settings = {field: config[element] for element, field in _STEP_CONTROL_FIELDS.items()
                if element in config}
    return JacobiAlgorithm(step_control=StepControl(rollback=False, **settings))
