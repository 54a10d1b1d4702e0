"""syssimx writes to an FMU only what the user set, as FMPy does, and passes the solver
tolerance to fmi2SetupExperiment (the user's, else the DefaultExperiment's).

keep_defaults declares its parameter h_min and its input u with start "0.000000" while the
model holds 1e-7 for both (an exporter printing with %f): writing the declared starts refuses
every step (h_min = 0) and zeroes y = u / h_min, which is 1 with the model's own values.
"""

from __future__ import annotations

import zipfile
from pathlib import Path

import fmpy
import numpy as np
import pytest
from fixture_fmus import fmu_path
from syssimx import Connection, CoSimComponent, FMUComponent, PortSpec, PortType, System, fmus
from syssimx.errors import ConfigurationError, SimulationError


def run_keep_defaults(component: FMUComponent, system: System | None = None) -> np.ndarray:
    if system is None:
        system = System("keep")
        system.add_component(component)
    system.initialize(0.0)
    return np.array(system.run(0.0, 0.1, 0.05)[component.name][1]["y"])


def test_declared_starts_the_user_never_set_are_not_written():
    keep = FMUComponent("K", fmu_path("keep_defaults"))
    assert keep.parameters["h_min"] == 0.0  # what the modelDescription declares
    y = run_keep_defaults(keep)
    assert list(y) == [1.0, 1.0, 1.0]
    fmpy_result = fmpy.simulate_fmu(fmu_path("keep_defaults"), stop_time=0.1,
                                    output_interval=0.05)
    assert list(fmpy_result["y"]) == list(y)


def test_an_input_never_set_reads_the_fmus_own_value():
    keep = FMUComponent("K", fmu_path("keep_defaults"))
    assert keep.inputs["u"].get() == 0.0  # the declared start, before the FMU runs
    run_keep_defaults(keep)
    assert keep.inputs["u"].get() == 1e-7
    assert keep.get_state()["u"]["value"] == 1e-7


def test_values_the_user_set_are_written():
    keep = FMUComponent("K", fmu_path("keep_defaults"))
    keep.set_parameters(h_min=2e-7)
    keep.set_inputs({"u": 3e-7})
    assert list(run_keep_defaults(keep)) == [1.5, 1.5, 1.5]


def test_a_parameter_changed_in_the_parameters_dict_is_written():
    keep = FMUComponent("K", fmu_path("keep_defaults"))
    keep.parameters["h_min"] = 4e-7
    assert list(run_keep_defaults(keep)) == [0.25, 0.25, 0.25]


def test_a_value_set_equal_to_the_declared_start_is_still_written():
    keep = FMUComponent("K", fmu_path("keep_defaults"))
    keep.set_parameters(h_min=0.0)
    with pytest.raises(SimulationError, match="h_min must be positive"):
        run_keep_defaults(keep)


def test_reinitialize_overrides_are_written_even_when_equal_to_the_declared_start():
    keep = FMUComponent("K", fmu_path("keep_defaults"))
    run_keep_defaults(keep)
    keep.reinitialize(0.1, h_min=0.0)
    assert keep.instance.getReal([keep.value_reference("h_min")]) == [0.0]
    keep.reinitialize(0.1)  # the override held for that instance only
    assert keep.instance.getReal([keep.value_reference("h_min")]) == [1e-7]


class Source(CoSimComponent):
    """A constant output."""

    def __init__(self, value: float) -> None:
        super().__init__("Source")
        self.output_specs["v"] = PortSpec("v", PortType.REAL, "out")
        self.value = value

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _update_output_states(self, t=None, event_names=None) -> None:
        self.outputs["v"].set(self.value, t)


def test_a_connected_input_is_driven_by_its_connection():
    keep = FMUComponent("K", fmu_path("keep_defaults"))
    system = System("driven")
    system.add_component(Source(5e-7))
    system.add_component(keep)
    system.add_connection(Connection("Source", "v", "K", "u"))
    assert list(run_keep_defaults(keep, system)) == [5.0, 5.0, 5.0]


# ------------------------------------------------------------------------------ tolerance
def pendulum_theta(component: FMUComponent, tolerance: float | None = None) -> np.ndarray:
    system = System("tolerance")
    system.add_component(component)
    system.initialize(0.0, tolerance=tolerance)
    return np.array(system.run(0.0, 2.0, 0.1)[component.name][1]["theta"])


def fmpy_theta(path: str, tolerance: float | None) -> np.ndarray:
    result = fmpy.simulate_fmu(path, stop_time=2.0, output_interval=0.1,
                               relative_tolerance=tolerance, start_values={"theta0": 1.0})
    return result["theta"]


def pendulum(path: str, **options) -> FMUComponent:
    component = FMUComponent("P", path, **options)
    component.set_parameters(theta0=1.0)
    return component


def test_the_component_tolerance_gives_fmpys_numbers():
    path = fmus.path("pendulum_cvode")
    ours = pendulum_theta(pendulum(path, tolerance=1e-3))
    np.testing.assert_allclose(ours, fmpy_theta(path, 1e-3), rtol=0, atol=1e-14)
    # the tolerance reached CVODE: its default (1e-6) gives other numbers
    assert np.max(np.abs(ours - pendulum_theta(pendulum(path)))) > 1e-6


def test_the_system_tolerance_serves_components_without_their_own():
    path = fmus.path("pendulum_cvode")
    np.testing.assert_allclose(pendulum_theta(pendulum(path), tolerance=1e-3),
                               fmpy_theta(path, 1e-3), rtol=0, atol=1e-14)
    np.testing.assert_allclose(pendulum_theta(pendulum(path, tolerance=1e-8), tolerance=1e-3),
                               fmpy_theta(path, 1e-8), rtol=0, atol=1e-14)


def with_default_tolerance(tmp_path: Path, tolerance: str) -> Path:
    source = Path(fmus.path("pendulum_cvode"))
    target = tmp_path / "pendulum_tolerance.fmu"
    with zipfile.ZipFile(source) as src, zipfile.ZipFile(target, "w") as dst:
        for item in src.infolist():
            data = src.read(item)
            if item.filename == "modelDescription.xml":
                data = data.replace(b"<DefaultExperiment ",
                                    b'<DefaultExperiment tolerance="%s" ' % tolerance.encode())
            dst.writestr(item, data)
    return target


def test_the_default_experiment_tolerance_is_the_default(tmp_path: Path):
    path = str(with_default_tolerance(tmp_path, "1e-3"))
    # FMPy passes the DefaultExperiment tolerance when it is given none
    np.testing.assert_allclose(pendulum_theta(pendulum(path)), fmpy_theta(path, None),
                               rtol=0, atol=1e-14)
    np.testing.assert_allclose(fmpy_theta(path, None), fmpy_theta(path, 1e-3), rtol=0, atol=0)


@pytest.mark.parametrize("tolerance", [0.0, -1e-6, float("nan"), "1e-6", True])
def test_a_tolerance_that_is_not_a_positive_number_is_refused(tolerance):
    with pytest.raises(ConfigurationError,
                       match=r"P: tolerance must be a positive number, got "):
        FMUComponent("P", fmus.path("pendulum_cvode"), tolerance=tolerance)
    component = FMUComponent("P", fmus.path("pendulum_cvode"))
    system = System("s")
    system.add_component(component)
    with pytest.raises(ConfigurationError, match=r"P: the tolerance given to System\.initialize "
                                                 r"must be a positive number"):
        system.initialize(0.0, tolerance=tolerance)
