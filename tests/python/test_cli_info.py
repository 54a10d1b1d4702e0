"""The command line without simulation: info, fmus and bad input."""

from __future__ import annotations

import zipfile
from pathlib import Path

import pytest
from syssimx.cli import main

MODEL_DESCRIPTION = """<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="Spring" guid="{spring-1}"
    description="A linear torsion spring" generationTool="hand">
  <CoSimulation modelIdentifier="spring" canGetAndSetFMUstate="true"
      canHandleVariableCommunicationStepSize="true"/>
  <UnitDefinitions>
    <Unit name="rad"/><Unit name="N.m"/><Unit name="N.m/rad"/>
  </UnitDefinitions>
  <TypeDefinitions>
    <SimpleType name="Angle"><Real unit="rad"/></SimpleType>
  </TypeDefinitions>
  <DefaultExperiment startTime="0" stopTime="2" stepSize="0.01"/>
  <ModelVariables>
    <ScalarVariable name="phi" valueReference="0" causality="input" variability="continuous">
      <Real declaredType="Angle" start="0"/></ScalarVariable>
    <ScalarVariable name="k" valueReference="1" causality="parameter" variability="fixed"
        description="stiffness"><Real unit="N.m/rad" start="12.5"/></ScalarVariable>
    <ScalarVariable name="tau" valueReference="2" causality="output" variability="continuous">
      <Real unit="N.m"/></ScalarVariable>
  </ModelVariables>
  <ModelStructure>
    <Outputs><Unknown index="3" dependencies="1"/></Outputs>
    <InitialUnknowns><Unknown index="3"/></InitialUnknowns>
  </ModelStructure>
</fmiModelDescription>
"""


@pytest.fixture
def build_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A build directory holding one FMU archive, models/spring.fmu (description only)."""
    (tmp_path / "models").mkdir()
    with zipfile.ZipFile(tmp_path / "models" / "spring.fmu", "w") as archive:
        archive.writestr("modelDescription.xml", MODEL_DESCRIPTION)
    monkeypatch.setenv("SYSSIMX_BUILD_DIR", str(tmp_path))
    return tmp_path


def test_info_lists_variables_capabilities_and_feedthrough(
    build_dir: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["info", str(build_dir / "models" / "spring.fmu")]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert "Model:            Spring" in lines
    assert "GUID:             {spring-1}" in lines
    assert "Default experiment: startTime=0, stopTime=2, stepSize=0.01" in lines
    assert "  canGetAndSetFMUstate                     yes" in lines
    assert "  canSerializeFMUstate                     no" in lines
    rows = [line.split() for line in lines[lines.index("Variables (3):") + 2:][:3]]
    # The input's unit comes from its declared type.
    assert rows == [
        ["phi", "input", "continuous", "Real", "rad", "0"],
        ["k", "parameter", "fixed", "Real", "N.m/rad", "12.5", "stiffness"],
        ["tau", "output", "continuous", "Real", "N.m"],
    ]
    assert lines[-1] == "  tau <- phi"


def test_bundled_fmus_are_listed_and_found_by_name(
    build_dir: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["fmus"]) == 0
    listing = capsys.readouterr().out.split()
    assert listing == ["spring", str(build_dir / "models" / "spring.fmu")]
    assert main(["info", "spring"]) == 0
    assert "Model:            Spring" in capsys.readouterr().out


def test_runtime_failures_exit_1_with_one_line(
    build_dir: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["info", "no_such_model"]) == 1
    error = capsys.readouterr().err
    assert error == ("syssimx: error: no FMU file 'no_such_model' and no bundled FMU of that "
                     "name; 'syssimx fmus' lists the 1 bundled FMUs\n")
    assert main(["info", "sprung"]) == 1
    assert "of that name (did you mean 'spring'?); " in capsys.readouterr().err
    not_a_zip = tmp_path / "broken.fmu"
    not_a_zip.write_text("not an archive")
    assert main(["info", str(not_a_zip)]) == 1
    error = capsys.readouterr().err
    assert error.startswith(f"syssimx: error: {not_a_zip} is not a readable FMU")
    assert "Traceback" not in error


@pytest.mark.parametrize(
    "argv",
    [
        [],
        ["frobnicate"],
        ["simulate", "spring", "--event", "theta:sideways"],
        ["simulate", "spring", "--set", "k"],
        ["simulate", "spring", "--stop-time", "soon"],
    ],
)
def test_usage_errors_exit_2(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert main(argv) == 2
    error = capsys.readouterr().err
    assert "usage: syssimx" in error and "Traceback" not in error
