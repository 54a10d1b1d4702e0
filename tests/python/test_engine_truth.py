"""One truth across C and Python: defaults and enums come from the engine header, the engine
judges option values, and a failure's exception follows the engine's error kind."""

from __future__ import annotations

import pytest
from fixture_fmus import fmu_path
from syssimx import (
    AlgebraicLoopError,
    Connection,
    FMUComponent,
    GaussSeidelAlgorithm,
    HybridAlgorithm,
    JacobiAlgorithm,
    SimulationError,
    System,
    fmus,
)
from syssimx.engine import defaults, enum_values


def test_option_defaults_are_the_engines():
    engine = defaults()
    loop = JacobiAlgorithm()
    assert (loop.tolerance, loop.max_iter, loop.damping, loop.loop_jacobian) == (
        engine.loop_tolerance, engine.loop_max_iterations, engine.loop_damping, "auto")
    assert loop.max_iter == 100
    hybrid = HybridAlgorithm()
    assert (hybrid.tol_time, hybrid.tol_value, hybrid.max_iter, hybrid.max_microsteps,
            hybrid.zeno_min_interval) == (engine.tol_time, engine.tol_value,
                                          engine.max_iterations, engine.max_microsteps,
                                          engine.zeno_min_interval)
    assert hybrid.method == "illinois"
    assert type(hybrid.coupling) is GaussSeidelAlgorithm
    assert type(System("S").algorithm) is GaussSeidelAlgorithm


def test_enum_names_come_from_the_header():
    assert enum_values("ssx_coupling", "SSX_") == {"gauss_seidel": 0, "jacobi": 1}
    assert GaussSeidelAlgorithm().coupling_value() == 0
    assert JacobiAlgorithm().coupling_value() == 1
    assert list(enum_values("ssx_loop_jacobian", "SSX_JACOBIAN_")) == ["auto",
                                                                      "finite_differences"]


def test_the_engine_judges_hybrid_options():
    with pytest.raises(ValueError) as info:
        HybridAlgorithm(tol_time=-1.0).validate()
    assert str(info.value).startswith(
        "HybridAlgorithm: the engine refuses tol_time=-1.0, tol_value=1e-09, max_iter=100, "
        "max_microsteps=10, zeno_min_interval=0.0: hybrid options: need tol_time > 0")


def non_finite_system(name: str) -> System:
    broken = FMUComponent(name, fmu_path("failing"))
    broken.set_parameters(fail_time=0.5, failure=4)  # 4: a NaN output from fail_time on
    broken.set_inputs({"u": 2.0})
    system = System("S")
    system.add_component(broken)
    # a NaN stops the run where it reaches an input
    system.add_component(FMUComponent("G", fmus.path("gain")))
    system.add_connection(Connection(name, "y", "G", "u", convert_units=False))
    system.initialize(0.0)
    return system


def test_the_exception_follows_the_error_kind_not_the_message():
    # the message names a component called "loop", yet no algebraic loop failed
    with pytest.raises(SimulationError) as info:
        non_finite_system("loop").run(0.0, 1.0, 0.25)
    assert type(info.value) is SimulationError
    assert not isinstance(info.value, AlgebraicLoopError)
    assert str(info.value).startswith("component 'loop': output 'y' is nan at t=0.75")
