"""The lean modelDescription reader gives what fmpy's read_model_description gives, for the
fields syssimx reads, on our FMUs and on the Reference FMUs; units "-", "1" and "" are
dimensionless."""

from __future__ import annotations

import logging
import os
import zipfile
from pathlib import Path

import pint
import pytest
from fmpy import read_model_description
from syssimx import Connection, FMUComponent, System, fmus, units
from syssimx.components.description_reader import read_description
from syssimx.errors import ConfigurationError


def reference_fmus() -> list[Path]:
    root = Path(os.environ.get("SYSSIMX_REFERENCE_FMUS")
                or Path(__file__).resolve().parents[3] / "shared" / "reference-fmus")
    return sorted((root / "fmi2").glob("*.fmu"))


VARIABLE_FIELDS = ("name", "valueReference", "type", "causality", "variability", "initial",
                   "description", "unit", "start")
INTERFACE_FIELDS = ("modelIdentifier", "canGetAndSetFMUstate", "canSerializeFMUstate",
                    "canBeInstantiatedOnlyOncePerProcess", "providesDirectionalDerivative",
                    "canHandleVariableCommunicationStepSize", "needsExecutionTool")


def both(path: Path):
    with zipfile.ZipFile(path) as archive, archive.open("modelDescription.xml") as stream:
        ours = read_description(stream, path)
    return ours, read_model_description(str(path), validate=False)


def assert_same(path: Path) -> None:
    ours, theirs = both(path)
    for name in ("fmiVersion", "modelName", "guid", "description", "generationTool"):
        assert getattr(ours, name) == getattr(theirs, name), name
    for name in INTERFACE_FIELDS:
        assert getattr(ours.coSimulation, name) == getattr(theirs.coSimulation, name), name
    for name in ("startTime", "stopTime", "stepSize", "tolerance"):
        assert getattr(ours.defaultExperiment, name) == getattr(theirs.defaultExperiment, name)
    assert len(ours.modelVariables) == len(theirs.modelVariables)
    for mine, fmpys in zip(ours.modelVariables, theirs.modelVariables, strict=True):
        for name in VARIABLE_FIELDS:
            assert getattr(mine, name) == getattr(fmpys, name), (mine.name, name)
        assert getattr(mine.declaredType, "name", None) == getattr(fmpys.declaredType, "name",
                                                                    None)
        assert getattr(mine.declaredType, "unit", None) == getattr(fmpys.declaredType, "unit",
                                                                    None)
    assert len(ours.outputs) == len(theirs.outputs)
    for mine, fmpys in zip(ours.outputs, theirs.outputs, strict=True):
        assert mine.variable.name == fmpys.variable.name
        assert (None if mine.dependencies is None else [v.name for v in mine.dependencies]) == \
            (None if fmpys.dependencies is None else [v.name for v in fmpys.dependencies])


@pytest.mark.parametrize("name", fmus.available())
def test_our_fmus_read_as_fmpy_reads_them(name: str):
    assert_same(Path(fmus.path(name)))


def test_reference_fmus_read_as_fmpy_reads_them():
    paths = reference_fmus()
    if not paths:
        pytest.skip("the Reference FMUs are not there (set SYSSIMX_REFERENCE_FMUS)")
    for path in paths:
        assert_same(path)


# ------------------------------------------------------------------------------ units
@pytest.mark.parametrize("unit", ["-", "1", "", " - "])
def test_dimensionless_spellings(unit: str):
    assert units.to_unit(unit) == units.ureg.dimensionless


@pytest.mark.parametrize("unit", ["m/s/", "--", "bogus_unit"])
def test_units_pint_cannot_read_give_a_message(unit: str):
    with pytest.raises(ValueError, match=f"unit '{unit}' is unknown to pint") as caught:
        units.to_unit(unit)
    assert str(caught.value).endswith(")") and "()" not in str(caught.value)


def test_an_fmu_with_unit_dash_loads_and_runs(caplog: pytest.LogCaptureFixture):
    with caplog.at_level(logging.WARNING):
        dash = FMUComponent("D", fmus.path("unit_dash"))
    assert caplog.messages == []
    assert dash.output_specs["y"].unit == "-"
    dash.set_inputs({"u": 1.5})
    system = System("dash")
    system.add_component(dash)
    system.initialize(0.0)
    assert list(system.run(0.0, 0.1, 0.1)["D"][1]["y"]) == [3.0, 3.0]
    assert dash.get_outputs()["y"] == 3.0 * units.ureg.dimensionless


def test_a_dimensionless_port_connects_to_dimensionless_not_to_metres():
    system = System("dash")
    system.add_component(FMUComponent("A", fmus.path("unit_dash")))
    system.add_component(FMUComponent("B", fmus.path("unit_dash")))
    system.add_component(FMUComponent("G", fmus.path("gain")))
    system.add_connection(Connection("A", "y", "B", "u"))
    with pytest.raises(ConfigurationError, match="incompatible units '-' and 'm'"):
        system.add_connection(Connection("A", "y", "G", "u"))
    assert units.conversion("-", "1") == (1.0, 0.0)
    with pytest.raises(pint.DimensionalityError):
        units.conversion("-", "m")


def test_no_syssimx_error_has_an_empty_message():
    from syssimx.errors import FMUFileError, SimulationError, SysSimXError

    assert str(SysSimXError()) == "Base class of every syssimx error."
    assert str(FMUFileError("")) == ("The .fmu file cannot be used: missing, a broken or "
                                     "hostile archive, an invalid")
    assert str(SimulationError("", component="P")).startswith("A run failed.")


def test_what_tools_write_into_annotations_is_ignored_as_fmpy_ignores_it(tmp_path: Path):
    with zipfile.ZipFile(fmus.path("gain")) as gain:
        entries = {name: gain.read(name) for name in gain.namelist()}
    text = entries["modelDescription.xml"].decode()
    text = text.replace("  <ModelVariables>", """  <VendorAnnotations><Tool name="t">
    <CoSimulation modelIdentifier="elsewhere"/>
    <ScalarVariable name="ghost" valueReference="9"><Real/></ScalarVariable>
  </Tool></VendorAnnotations>
  <ModelVariables>""")
    text = text.replace('<Real start="1"/>', '<Real start="1"/><Annotations><Tool name="t">'
                        '<Real start="not a number"/><Unknown index="99"/></Tool></Annotations>')
    entries["modelDescription.xml"] = text.encode()
    path = tmp_path / "annotated.fmu"
    with zipfile.ZipFile(path, "w") as archive:
        for name, data in entries.items():
            archive.writestr(name, data)
    assert_same(path)
    ours, _ = both(path)
    assert [v.name for v in ours.modelVariables] == ["y", "u", "k"]
    assert ours.coSimulation.modelIdentifier == "gain"
