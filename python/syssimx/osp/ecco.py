"""libcosim's `ecco` algorithm as syssimx runs it: Jacobi with the communication step chosen
without rollback (like ECCO, only the coming steps adapt) by the energy residual of the power
bonds under ECCO's PI controller, with the <EccoConfiguration>'s settings. Inputs are held, as
libcosim holds them."""

from __future__ import annotations

from ..errors import ConfigurationError
from ..system.algorithms import JacobiAlgorithm, StepControl
from .build import PowerBond
from .errors import OSPError

# <EccoConfiguration> element -> StepControl field
_STEP_CONTROL_FIELDS = {"SafetyFactor": "safety", "StepSize": "initial_step",
                        "MinimumStepSize": "min_step", "MaximumStepSize": "max_step",
                        "RelativeTolerance": "rtol", "AbsoluteTolerance": "atol",
                        "MinimumChangeRate": "min_change", "MaximumChangeRate": "max_change",
                        "ProportionalGain": "proportional_gain",
                        "IntegralGain": "integral_gain"}


def bond_ends(bond: PowerBond, where: str) -> tuple[tuple[str, str], tuple[str, str]]:
    """The two inputs a bond joins: the destinations of its two connections, which run in
    opposite directions between two simulators."""
    if len(bond.connections) != 2:
        raise OSPError(f"{where}: power bond {bond.name!r} has {len(bond.connections)} "
                       "connections; a power bond is two, one each way between two simulators")
    (a_out, a_in), (b_out, b_in) = bond.connections
    if a_out[0] != b_in[0] or b_out[0] != a_in[0] or a_out[0] == b_out[0]:
        raise OSPError(f"{where}: power bond {bond.name!r}: its connections "
                       f"{a_out[0]}.{a_out[1]} -> {a_in[0]}.{a_in[1]} and "
                       f"{b_out[0]}.{b_out[1]} -> {b_in[0]}.{b_in[1]} do not run each way "
                       "between two simulators")
    return a_in, b_in


def ecco_algorithm(config: dict[str, float], bonds: list[PowerBond],
                   where: str) -> JacobiAlgorithm:
    """The algorithm an <Algorithm>ecco</Algorithm> structure runs with: the energy residual
    of its power bonds (libcosim refuses a structure without any; syssimx then controls the
    coupling error of every connection)."""
    settings: dict[str, object] = {field: config[element]
                                   for element, field in _STEP_CONTROL_FIELDS.items()
                                   if element in config}
    if bonds:
        settings.update(error="energy",
                        power_bonds=tuple(bond_ends(bond, where) for bond in bonds))
    algorithm = JacobiAlgorithm(step_control=StepControl(rollback=False, **settings))  # type: ignore[arg-type]
    try:
        algorithm.validate()
    except ConfigurationError as exc:
        raise OSPError(f"{where}: <EccoConfiguration>: {exc}") from exc
    return algorithm
