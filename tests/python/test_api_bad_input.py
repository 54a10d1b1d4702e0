"""Bad input is a clear exception before anything runs."""

from __future__ import annotations

import zipfile
from pathlib import Path

import pint
import pytest
from syssimx import (
    ConfigurationError,
    Connection,
    CoSimComponent,
    EventConnection,
    FMUComponent,
    FMUFileError,
    PortSpec,
    PortType,
    System,
    fmus,
    units,
)

DESCRIPTION = """<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="Fake" guid="{fake}">
  {interface}
  <ModelVariables>
    <ScalarVariable name="u" valueReference="0" causality="input" variability="continuous">
      <Real start="0"/></ScalarVariable>
    <ScalarVariable name="y" valueReference="1" causality="output" variability="continuous">
      <Real/></ScalarVariable>
  </ModelVariables>
  <ModelStructure><Outputs><Unknown index="2"/></Outputs></ModelStructure>
</fmiModelDescription>
"""
CO_SIMULATION = '<CoSimulation modelIdentifier="fake"/>'
MODEL_EXCHANGE = '<ModelExchange modelIdentifier="fake"/>'


def archive(path: Path, files: dict[str, str]) -> Path:
    with zipfile.ZipFile(path, "w") as zf:
        for name, text in files.items():
            zf.writestr(name, text)
    return path


def test_missing_file(tmp_path: Path):
    with pytest.raises(FMUFileError, match="not found"):
        FMUComponent("X", tmp_path / "nothing.fmu")


def test_not_a_zip(tmp_path: Path):
    path = tmp_path / "text.fmu"
    path.write_text("not an archive")
    with pytest.raises(FMUFileError, match="not a zip"):
        FMUComponent("X", path)


def test_zip_without_model_description(tmp_path: Path):
    path = archive(tmp_path / "empty.fmu", {"readme.txt": "hi"})
    with pytest.raises(FMUFileError, match=r"no modelDescription\.xml"):
        FMUComponent("X", path)


def test_no_linux64_binary(tmp_path: Path):
    path = archive(tmp_path / "nobin.fmu", {
        "modelDescription.xml": DESCRIPTION.replace("{interface}", CO_SIMULATION),
        "binaries/win64/fake.dll": "MZ"})
    with pytest.raises(FMUFileError, match="no linux64 binary"):
        FMUComponent("X", path)


def test_model_exchange_only(tmp_path: Path):
    """A Model-Exchange-only FMU is run as Model Exchange ("auto"); asking for Co-Simulation
    names what the FMU has."""
    path = archive(tmp_path / "me.fmu", {
        "modelDescription.xml": DESCRIPTION.replace("{interface}", MODEL_EXCHANGE),
        "binaries/linux64/fake.so": ""})
    with pytest.raises(ConfigurationError, match=r"component 'X': me\.fmu has no co-simulation "
                       r"interface \(it has model-exchange\)"):
        FMUComponent("X", path, interface="co-simulation")
    with pytest.raises(FMUFileError, match=r"cannot load binaries/linux64/fake\.so"):
        FMUComponent("X", path)


def test_binary_that_does_not_load(tmp_path: Path):
    path = archive(tmp_path / "broken.fmu", {
        "modelDescription.xml": DESCRIPTION.replace("{interface}", CO_SIMULATION),
        "binaries/linux64/fake.so": "not an ELF file"})
    with pytest.raises(FMUFileError, match="cannot load"):
        FMUComponent("X", path)


@pytest.fixture
def pendulum() -> FMUComponent:
    return FMUComponent("P", fmus.path("pendulum_euler"))


def test_unknown_parameter_names_component_and_known_parameters(pendulum: FMUComponent):
    with pytest.raises(ConfigurationError, match=r"'P' has no parameter 'lenght'.*'L'"):
        pendulum.set_parameters(lenght=1.0)


def test_parameter_with_incompatible_unit(pendulum: FMUComponent):
    with pytest.raises(ConfigurationError, match="not convertible"):
        pendulum.set_parameters(L=units.Quantity(1.0, "s"))


def test_parameter_of_wrong_type(pendulum: FMUComponent):
    with pytest.raises(ConfigurationError, match="is Real"):
        pendulum.set_parameters(L="long")


def test_input_of_wrong_type_and_unknown_input(pendulum: FMUComponent):
    with pytest.raises(TypeError, match="REAL"):
        pendulum.set_inputs({"torque": "strong"})
    with pytest.raises(ConfigurationError, match="no input 'force'"):
        pendulum.set_inputs({"force": 1.0})


class Source(CoSimComponent):
    def __init__(self, name: str, unit: str | None = None):
        super().__init__(name)
        self.output_specs["y"] = PortSpec("y", PortType.REAL, "out", unit)
        self.output_specs["n"] = PortSpec("n", PortType.INT, "out")

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _update_output_states(self, t=None, event_names=None) -> None:
        self.outputs["y"].set(1.0, t)


def system_with(*components: CoSimComponent) -> System:
    system = System("S")
    for component in components:
        system.add_component(component)
    return system


def test_unknown_component_and_port_name_what_exists(pendulum: FMUComponent):
    system = system_with(Source("Src", "N.m"), pendulum)
    with pytest.raises(ConfigurationError, match=r"unknown component 'Nope'.*P.*Src"):
        system.add_connection(Connection("Nope", "y", "P", "torque"))
    with pytest.raises(ConfigurationError, match=r"no output 'z'.*\['n', 'y'\]"):
        system.add_connection(Connection("Src", "z", "P", "torque"))
    with pytest.raises(ConfigurationError, match=r"no input 'force'.*torque"):
        system.add_connection(Connection("Src", "y", "P", "force"))


def test_incompatible_units(pendulum: FMUComponent):
    system = system_with(Source("Src", "m/s"), pendulum)
    with pytest.raises(ConfigurationError, match=r"incompatible units 'm/s' and 'N\.m'"):
        system.add_connection(Connection("Src", "y", "P", "torque"))
    with pytest.raises(pint.DimensionalityError):
        units.conversion("m/s", "N.m")


def test_incompatible_types():
    class IntSink(Source):
        def __init__(self, name: str):
            super().__init__(name)
            self.input_specs["k"] = PortSpec("k", PortType.INT, "in")

    system = system_with(Source("Src"), IntSink("Dst"))
    with pytest.raises(ConfigurationError, match="REAL output cannot drive a INT input"):
        system.add_connection(Connection("Src", "y", "Dst", "k"))


def test_one_driver_per_input(pendulum: FMUComponent):
    system = system_with(Source("A", "N.m"), Source("B", "N.m"), pendulum)
    system.add_connection(Connection("A", "y", "P", "torque"))
    with pytest.raises(ConfigurationError, match=r"already driven by A\.y"):
        system.add_connection(Connection("B", "y", "P", "torque"))


def test_event_connection_checks(pendulum: FMUComponent):
    system = system_with(pendulum)
    with pytest.raises(ConfigurationError, match="no event indicator 'hit'"):
        system.add_event_connection(EventConnection("P", "hit", "P", "reset"))
    pendulum.add_event_indicator("hit", variable="theta", direction=-1)
    with pytest.raises(ConfigurationError, match="no EVENT input 'reset'"):
        system.add_event_connection(EventConnection("P", "hit", "P", "reset"))
    pendulum.input_specs["reset"] = PortSpec("reset", PortType.EVENT, "in")
    system.add_event_connection(EventConnection("P", "hit", "P", "reset"))
    with pytest.raises(ConfigurationError, match="handles no events"):
        system.initialize(0.0)


def test_indicator_on_unknown_variable(pendulum: FMUComponent):
    with pytest.raises(ConfigurationError, match="'phi' is not an output"):
        pendulum.add_event_indicator("hit", variable="phi")


def test_indicators_without_rollback_fail_at_initialize():
    source = Source("Src")
    source.add_event_indicator("up", func=lambda c: 1.0)
    system = system_with(source)
    with pytest.raises(ConfigurationError, match="'Src' has event indicators but cannot roll"):
        system.initialize(0.0)


@pytest.mark.parametrize(("t0", "tf", "dt", "message"), [
    (0.0, 1.0, 0.0, "dt must be positive"),
    (0.0, 1.0, -0.1, "dt must be positive"),
    (0.0, -1.0, 0.1, "before t0"),
    (0.0, float("nan"), 0.1, "finite"),
    (0.5, 1.0, 0.1, "system is at t=0.0"),
])
def test_bad_times(pendulum: FMUComponent, t0: float, tf: float, dt: float, message: str):
    system = system_with(pendulum)
    system.initialize(0.0)
    with pytest.raises(ConfigurationError, match=message):
        system.run(t0, tf, dt)


def test_run_before_initialize(pendulum: FMUComponent):
    with pytest.raises(ConfigurationError, match="initialize"):
        system_with(pendulum).run(0.0, 1.0, 0.1)


def test_no_zero_length_step(pendulum: FMUComponent):
    pendulum.initialize(0.0)
    with pytest.raises(ValueError, match="positive step"):
        pendulum.instance.doStep(0.0, 0.0)


def test_component_initialized_elsewhere_needs_a_new_initialize(pendulum: FMUComponent):
    system = system_with(pendulum)
    system.initialize(0.0)
    pendulum.initialize(0.0)  # on its own: the component now lives in a private system
    with pytest.raises(ConfigurationError, match="initialized elsewhere"):
        system.run(0.0, 1.0, 0.1)
    system.initialize(0.0)
    assert system.run(0.0, 0.1, 0.1)["P"][0][-1] == 0.1
