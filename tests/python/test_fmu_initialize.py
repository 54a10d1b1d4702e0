"""FMUComponent.reinitialize is one engine call (ssx_fmu_initialize); SysSimX subclasses that
override the start hooks still write their values, in initialization mode."""

from __future__ import annotations

import pytest
from syssimx import FMUComponent, System, fmus

THETA0 = 0.5


class HookedPendulum(FMUComponent):
    """Overrides both hooks as a SysSimX subclass may: they run, and their writes count."""

    def __init__(self, theta0_written: float) -> None:
        super().__init__("P", fmus.path("pendulum_euler"))
        self.theta0_written = theta0_written
        self.calls: list[tuple[str, str]] = []

    def _apply_parameters_starts(self) -> None:
        self.calls.append(("parameters", self.instance.mode))
        super()._apply_parameters_starts()
        self.instance.setReal([self.value_reference("theta0")], [self.theta0_written])

    def _apply_input_starts(self) -> None:
        self.calls.append(("inputs", self.instance.mode))
        super()._apply_input_starts()


def _theta(component: FMUComponent) -> float:
    return component.instance.getReal([component.value_reference("theta")])[0]


def test_plain_component_writes_the_user_values_in_one_engine_call() -> None:
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.set_parameters(theta0=THETA0)
    pendulum.reinitialize(0.0)
    assert pendulum.instance.mode == "step"
    assert _theta(pendulum) == THETA0
    counters = pendulum.instance.counters()
    # one instantiation; theta0 written once (one Real write), the theta read above
    assert (counters["instantiate"], counters["set_values"], counters["get_values"]) == (1, 1, 1)


def test_overridden_start_hooks_run_in_initialization_mode() -> None:
    pendulum = HookedPendulum(theta0_written=0.25)
    pendulum.set_parameters(theta0=THETA0)
    pendulum.reinitialize(0.0)
    assert pendulum.calls == [("parameters", "init"), ("inputs", "init")]
    assert pendulum.instance.mode == "step"
    assert _theta(pendulum) == 0.25  # the hook wrote after the parameters the user set


def test_overridden_hooks_run_when_a_system_initializes() -> None:
    pendulum = HookedPendulum(theta0_written=0.3)
    system = System("hooks")
    system.add_component(pendulum)
    system.initialize(0.0)
    result = system.run(0.0, 0.1, 0.05)
    assert pendulum.calls == [("parameters", "init"), ("inputs", "init")]
    _, data = result["P"]
    assert data["theta"][0] == 0.3


def test_a_failing_hook_raises_its_own_exception_and_a_new_instance_recovers() -> None:
    class Refusing(HookedPendulum):
        refuse = True

        def _apply_input_starts(self) -> None:
            if self.refuse:
                raise ValueError("no inputs today")
            super()._apply_input_starts()

    pendulum = Refusing(theta0_written=0.25)
    with pytest.raises(ValueError, match="no inputs today"):
        pendulum.reinitialize(0.0)
    assert pendulum.instance.mode == "init"  # never left initialization mode
    pendulum.refuse = False
    pendulum.theta0_written = 0.125
    pendulum.reinitialize(0.0)
    assert pendulum.instance.mode == "step"
    assert _theta(pendulum) == 0.125
