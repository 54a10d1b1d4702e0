"""SysSimX's algorithm names and options: the syssimx.algorithms namespace, IJCSAAlgorithm,
HybridAlgorithm's sign_tolerance, max_deferrals, gauss_seidel_algorithm and
raise_on_missed_event, and result.events read the way SysSimX code reads it."""

from __future__ import annotations

import dataclasses

import numpy as np
import pendulum_wall
import pytest
import syssimx
import syssimx.algorithms
from syssimx import (
    Connection,
    CoSimComponent,
    EventConnection,
    FMUComponent,
    GaussSeidelAlgorithm,
    HybridAlgorithm,
    IJCSAAlgorithm,
    JacobiAlgorithm,
    PortSpec,
    PortType,
    System,
    fmus,
)
from syssimx.core.events import DenseTime

QUARTER_PERIOD = pendulum_wall.QUARTER_PERIOD


def test_the_namespaces_hold_the_same_classes():
    for name in ("GaussSeidelAlgorithm", "HybridAlgorithm", "IJCSAAlgorithm", "JacobiAlgorithm"):
        assert getattr(syssimx.algorithms, name) is getattr(syssimx.system.algorithms, name)
        assert getattr(syssimx.algorithms, name) is getattr(syssimx, name)
    assert isinstance(IJCSAAlgorithm(), syssimx.algorithms.Algorithm)


def loop_system(algorithm: JacobiAlgorithm) -> System:
    """PI controller and gain in a direct-feedthrough loop (an algebraic loop)."""
    controller = FMUComponent("PI", fmus.path("pi_controller"))
    controller.set_parameters(kp=0.5, ki=1.0, integral0=1.0)
    gain = FMUComponent("Gain", fmus.path("gain"))
    gain.set_parameters(k=0.5)
    system = System("loop")
    system.add_component(controller)
    system.add_component(gain)
    system.add_connection(Connection("PI", "u", "Gain", "u"))
    system.add_connection(Connection("Gain", "y", "PI", "measurement"))
    system.set_algorithm(algorithm)
    system.initialize(0.0)
    return system


def test_ijcsa_solves_the_loop_with_sysimx_option_names():
    algorithm = IJCSAAlgorithm(max_iter=7, tol=1e-12)
    assert (algorithm.max_iter, algorithm.tolerance, algorithm.tol) == (7, 1e-12, 1e-12)
    algorithm.tol = 1e-13
    assert algorithm.tolerance == 1e-13 and algorithm.name == "IJCSA"
    result = loop_system(algorithm).run(0.0, 1.0, 0.1)
    reference = loop_system(GaussSeidelAlgorithm(tolerance=1e-13, max_iter=7)).run(0.0, 1.0, 0.1)
    u, y = result["PI"][1]["u"], result["Gain"][1]["y"]
    np.testing.assert_allclose(y, 0.5 * u, rtol=0, atol=1e-13)  # the loop holds at every sample
    np.testing.assert_array_equal(u, reference["PI"][1]["u"])
    assert result.statistics.loop_solves == reference.statistics.loop_solves == 11


def wall(solver: str = "cvode", direction: int = -1, **options: object
         ) -> tuple[System, FMUComponent]:
    pendulum = FMUComponent("P", fmus.path(f"pendulum_{solver}"))
    pendulum.set_parameters(theta0=0.5, omega0=0.0, cvode_relative_tolerance=1e-10)
    pendulum.add_event_indicator("wall_hit", variable="theta", direction=direction)
    pendulum.add_event_handler("omega_invert", pendulum_wall.bounce)
    system = System("wall")
    system.add_component(pendulum)
    system.add_event_connection(EventConnection("P", "wall_hit", "P", "omega_invert"))
    system.set_algorithm(HybridAlgorithm(tol_time=1e-9, **options))  # type: ignore[arg-type]
    system.initialize(0.0)
    return system, pendulum


def event_times(system: System, tf: float = 2.0) -> list[float]:
    return [e.t for e in system.run(0.0, tf, 0.05).events]


def test_sign_tolerance_is_accepted_and_changes_nothing_here():
    # With direction 0 the bounce leaves theta within the localization residue of zero, where
    # SysSimX needs sign_tolerance not to fire again; the engine tracks the side itself.
    runs = [event_times(wall(direction=0, sign_tolerance=tolerance)[0])
            for tolerance in (0.0, 1e-10, 1e-3)]
    assert runs[0] == runs[1] == runs[2]
    np.testing.assert_allclose(runs[0], [QUARTER_PERIOD, 3 * QUARTER_PERIOD], atol=1e-8)
    with pytest.raises(ValueError, match=r"sign_tolerance must be a finite number >= 0, got -1"):
        HybridAlgorithm(sign_tolerance=-1).validate()


class Torque(CoSimComponent):
    """A torque ramp 2 t upstream of the pendulum: the event source's input moves within
    every step (where SysSimX's trial and accepted trajectories part)."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.output_specs["tau"] = PortSpec("tau", PortType.REAL, "out", "N.m")

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        self.outputs["tau"].set(2.0 * (t or 0.0), t)

    def snapshot_state(self) -> None:
        return None  # no state: the output is a function of time

    def restore_state(self, snapshot: None, t: float) -> None:
        pass


def driven_wall(**options: object) -> System:
    system, _ = wall(**options)
    system.add_component(Torque("Drive"))
    system.add_connection(Connection("Drive", "tau", "P", "torque"))
    system.initialize(0.0)
    return system


def test_no_deferral_and_no_missed_event_on_a_driven_event_source():
    strict = driven_wall(max_deferrals=0, raise_on_missed_event=True)
    result = strict.run(0.0, 2.0, 0.05)
    default = driven_wall().run(0.0, 2.0, 0.05)
    assert [e.t for e in result.events] == [e.t for e in default.events]
    assert len(result.events) == 2 and strict.algorithm.missed_events == []
    # every event is dispatched where the accepted trajectory has crossed: theta <= 0 at the
    # located instant, > 0 at the sample before it
    t, values = result["P"]
    for event in result.events:
        at = np.flatnonzero((t == event.t) & (result.micro == 0))[0]
        assert values["theta"][at] <= 0.0 < values["theta"][at - 1]


def test_gauss_seidel_algorithm_is_the_coupling():
    algorithm = HybridAlgorithm(gauss_seidel_algorithm=JacobiAlgorithm(tolerance=1e-8))
    assert algorithm.coupling.name == "Jacobi" and algorithm.coupling.tolerance == 1e-8
    assert algorithm.gauss_seidel_algorithm is algorithm.coupling
    algorithm.gauss_seidel_algorithm = GaussSeidelAlgorithm()
    assert algorithm.coupling.name == "Gauss-Seidel"
    assert dataclasses.replace(algorithm, tol_time=1e-6).coupling is algorithm.coupling
    jacobi = event_times(driven_wall(gauss_seidel_algorithm=JacobiAlgorithm()))
    assert jacobi == event_times(driven_wall(coupling=JacobiAlgorithm()))


def test_result_events_read_as_sysimx_reads_them():
    system, _ = wall(direction=-1)
    result = system.run(0.0, 3.0, 0.05)
    key = ("P", "wall_hit")
    times = result.events[key]
    assert all(isinstance(t, DenseTime) and t.micro == 0 for t in times)
    assert [t.t for t in times] == [e.t for e in result.events]
    assert times[0].t == pytest.approx(QUARTER_PERIOD, abs=1e-9)
    assert key in result.events and ("P", "other") not in result.events
    assert result.events.keys() == [key] and result.events.values() == [times]
    assert dict(result.events.items()) == system.history.get_all_event_histories()
    assert result.events.get(("P", "other"), []) == []
    assert len(result.events) == 3 and result.events[-1].event == "wall_hit"
    with pytest.raises(KeyError, match=r"no event \('P', 'floor'\); events: \[\('P', "
                       r"'wall_hit'\)\]"):
        result.events["P", "floor"]
