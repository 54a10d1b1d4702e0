"""The power-bonded OSP system of libcosim's ECCO comparison (ecco_structure.py), read by
syssimx.osp and run against its monolithic solution (solve_ivp, rtol 1e-12). libcosim itself
runs in benchmarks/ecco_vs_libcosim.py; its figures on this file are quoted here as constants.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest
from ecco_structure import STOP_TIME, Ecco, monolithic, write_structure
from syssimx import JacobiAlgorithm, StepControl
from syssimx.osp import read as read_osp

OUTPUT_STEP = 0.05  # the file's MaximumStepSize: the output grid bounds no step
# libcosim 0.0.6 (libcosimpy) on the file with tolerance 1e-3: its macro steps and end error
LIBCOSIM_STEPS, LIBCOSIM_END_ERROR = 3497, 7.09e-3


def run(structure: Path, algorithm: JacobiAlgorithm | None = None,
        step: float = OUTPUT_STEP) -> tuple[float, float, object]:
    """Largest and end |theta error| over the output grid, and the statistics."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the reader's note on ECCO's PI settings
        system = read_osp(structure).system
    if algorithm is not None:
        system.set_algorithm(algorithm)
    system.initialize(0.0)
    result = system.run(0.0, STOP_TIME, step)
    t, pendulum = result["Pendulum"]
    error = np.abs(pendulum["theta"] - monolithic(t))
    return float(error.max()), float(error[-1]), result.statistics


def test_the_file_as_read_runs_like_libcosim_ecco(tmp_path: Path):
    """<Algorithm>ecco as syssimx maps it: Jacobi, held inputs, steps chosen without rollback
    by the bond's energy residual under ECCO's PI controller, with the file's settings. Its
    step count and error are libcosim's to within a factor of 2 (measured 2347 steps and 9.3e-3
    against 3497 and 7.1e-3; the two differ in when the spring's torque reaches the pendulum)."""
    _, end, stats = run(write_structure(tmp_path, Ecco(1e-3)))
    assert LIBCOSIM_STEPS / 2 < stats.macro_steps < 2 * LIBCOSIM_STEPS
    assert LIBCOSIM_END_ERROR / 2 < end < 2 * LIBCOSIM_END_ERROR
    assert stats.rejected_steps == 0
    assert 1e-5 <= stats.smallest_step <= stats.largest_step <= 0.05


def test_the_energy_residual_with_second_order_inputs(tmp_path: Path):
    """The same controller with input_order=2: 249 steps for 7.1e-5 (measured)."""
    structure = write_structure(tmp_path, Ecco(1e-3))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        control = read_osp(structure).system.algorithm.step_control
    assert control.error == "energy"
    _, end, stats = run(structure, JacobiAlgorithm(input_order=2, step_control=control))
    assert end < LIBCOSIM_END_ERROR / 50 and stats.macro_steps < LIBCOSIM_STEPS / 10


def test_held_inputs_under_the_coupling_error_stay_within_ten_times_the_tolerance(
        tmp_path: Path):
    """syssimx's own error measure with held inputs: the coupling error of held inputs grows
    like h, so the steps are short (measured 14 059 for 1.08e-3)."""
    ecco = Ecco(1e-3)
    control = StepControl(rtol=1e-3, atol=1e-3, min_step=ecco.min_step, max_step=ecco.max_step,
                          initial_step=ecco.step_size, safety=ecco.safety, rollback=False)
    worst, _, stats = run(write_structure(tmp_path, ecco), JacobiAlgorithm(step_control=control))
    assert worst < 10 * 1e-3
    assert stats.rejected_steps == 0


@pytest.mark.parametrize(("tolerance", "most_steps"), [
    (1e-3, 300),  # measured 144 steps, end error 4.5e-4
    (1e-4, 550),  # 272, 4.2e-5
    (1e-5, 1100),  # 556, 4.6e-6
])
def test_second_order_inputs_reach_the_tolerance_in_few_steps(tmp_path: Path, tolerance,
                                                               most_steps):
    ecco = Ecco(tolerance)
    control = StepControl(rtol=tolerance, atol=tolerance, min_step=ecco.min_step,
                          max_step=ecco.max_step, initial_step=ecco.step_size,
                          safety=ecco.safety, rollback=False)
    worst, end, stats = run(write_structure(tmp_path, ecco),
                            JacobiAlgorithm(input_order=2, step_control=control))
    assert end < tolerance and worst < 2 * tolerance
    assert stats.macro_steps < most_steps and stats.rejected_steps == 0


def test_power_bonds_are_checked_naming_the_input(tmp_path: Path):
    structure = write_structure(tmp_path, Ecco(1e-3))
    for bonds, named in (
            (((("Pendulum", "torq"), ("Spring", "omega1")),), "Pendulum.torq is not an input"),
            (((("Pendulum", "torque"), ("Spring", "theta2")),),  # not connected
             r"power bond 0: input \d of 'Spring' must be connected to an output of "
             "'Pendulum'")):
        control = StepControl(error="energy", power_bonds=bonds, rollback=False)
        with pytest.raises(Exception, match=named):
            run(structure, JacobiAlgorithm(step_control=control))
    with pytest.raises(ValueError, match="'energy' needs power_bonds"):
        JacobiAlgorithm(step_control=StepControl(error="energy")).validate()


def test_smaller_error_than_libcosim_ecco_for_its_number_of_steps(tmp_path: Path):
    """On libcosim's 3497 macro steps, held inputs give libcosim's error (7.1e-3: its adaptive
    steps do no better than the same number of even ones); second-order inputs give 1.9e-7.
    Adaptive second-order steps reach 4.5e-4 in 144 steps."""
    structure = write_structure(tmp_path, Ecco(1e-3))
    fixed = STOP_TIME / LIBCOSIM_STEPS
    _, held, _ = run(structure, JacobiAlgorithm(), fixed)
    assert held == pytest.approx(LIBCOSIM_END_ERROR, rel=0.05)  # measured 7.11e-3
    _, ours, stats = run(structure, JacobiAlgorithm(input_order=2), fixed)
    assert stats.macro_steps == LIBCOSIM_STEPS
    assert ours < LIBCOSIM_END_ERROR / 1000  # measured 1.9e-7
