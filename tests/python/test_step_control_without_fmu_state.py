"""An FMU that does not declare canGetAndSetFMUstate is never asked for its state: a step
control that rolls back is refused at initialize, naming the component; one without rollback
runs without a single state save (issue 34, item 10: 6 678 fmi2GetFMUstate
calls to such an FMU before)."""

from __future__ import annotations

import zipfile
from pathlib import Path

import pytest
from syssimx import Connection, FMUComponent, GaussSeidelAlgorithm, StepControl, System, fmus
from syssimx.errors import ConfigurationError


def without_fmu_state(source: str, target: Path) -> str:
    """A copy of the FMU whose description declares no FMU state (the binary is unchanged)."""
    with zipfile.ZipFile(source) as original, zipfile.ZipFile(target, "w") as copy:
        for item in original.infolist():
            data = original.read(item)
            if item.filename == "modelDescription.xml":
                data = data.replace(b'canGetAndSetFMUstate="true"', b'canGetAndSetFMUstate="false"')
                data = data.replace(b'canSerializeFMUstate="true"', b'canSerializeFMUstate="false"')
                assert b'canGetAndSetFMUstate="false"' in data
            copy.writestr(item, data)
    return str(target)


def pendulum_and_spring(tmp_path: Path, rollback: bool) -> System:
    stateless = without_fmu_state(fmus.path("pendulum_cvode"), tmp_path / "stateless.fmu")
    system = System("pendulum and spring")
    pendulum = FMUComponent("P", stateless)
    pendulum.set_parameters(theta0=0.5)
    spring = FMUComponent("Spring", fmus.path("torsion_spring"))
    system.add_component(pendulum)
    system.add_component(spring)
    system.add_connection(Connection("P", "theta", "Spring", "theta1"))
    system.add_connection(Connection("P", "omega", "Spring", "omega1"))
    system.add_connection(Connection("Spring", "tau1", "P", "torque"))
    control = StepControl(rtol=1e-4, atol=1e-4, rollback=rollback)
    system.set_algorithm(GaussSeidelAlgorithm(input_order=1, step_control=control))
    return system


def test_a_step_control_that_rolls_back_is_refused_at_initialize(tmp_path: Path):
    """Before: the run went on, calling fmi2GetFMUstate before every step."""
    system = pendulum_and_spring(tmp_path, rollback=True)
    assert not system.components["P"].can_get_set_state
    with pytest.raises(ConfigurationError) as caught:
        system.initialize(0.0)
    message = str(caught.value)
    assert "component 'P' cannot save and restore its state" in message
    assert "canGetAndSetFMUstate" in message and "rollback off" in message


def test_a_step_control_without_rollback_never_saves_a_state(tmp_path: Path):
    system = pendulum_and_spring(tmp_path, rollback=False)
    system.initialize(0.0)
    result = system.run(0.0, 1.0, 0.1)
    stats = result.statistics
    assert stats.accepted_steps > 10
    assert stats.state_saves == 0 and stats.state_restores == 0
