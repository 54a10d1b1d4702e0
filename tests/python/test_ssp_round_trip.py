"""The coupled pendulums built in Python, exported with System.to_ssp, checked against the SSP
schema, read by FMPy's SSP reader, and read back by syssimx.ssp giving the same numbers."""

from __future__ import annotations

import zipfile
from pathlib import Path

import coupled_pendulums as coupled_pendulums_example
import numpy as np
import pytest
from fmpy.ssp import ssd as fmpy_ssd
from lxml import etree
from syssimx import (
    GaussSeidelAlgorithm,
    JacobiAlgorithm,
    System,
)
from syssimx.ssp import SSPError, load, read

TF, DT = 2.0, 0.01


def coupled_pendulums(algorithm: JacobiAlgorithm) -> System:
    """examples/coupled_pendulums, the spring's torque into P2 as 0.5 * tau2 + 0.1."""
    return coupled_pendulums_example.build(algorithm, torque2_factor=0.5, torque2_offset=0.1)


def thetas(system: System) -> np.ndarray:
    system.initialize(0.0)
    result = system.run(0.0, TF, DT)
    return np.array([result["P1"][1]["theta"], result["P2"][1]["theta"]])


@pytest.mark.parametrize("algorithm", [JacobiAlgorithm, GaussSeidelAlgorithm])
def test_export_then_import_gives_the_same_numbers(tmp_path: Path, algorithm: type) -> None:
    original = coupled_pendulums(algorithm())
    path = original.to_ssp(tmp_path / "pendulums.ssp", 0.0, TF, DT)
    imported = read(path)
    assert imported.experiment.start_time == 0.0
    assert imported.experiment.stop_time == TF
    assert imported.experiment.step_size == DT
    assert imported.system.connections == original.connections
    assert {n: c.user_parameters() for n, c in imported.system.components.items()} \
        == {n: c.user_parameters() for n, c in original.components.items()}
    imported.system.set_algorithm(algorithm())
    expected, got = thetas(original), thetas(imported.system)
    assert np.abs(got - expected).max() <= 1e-12
    assert np.abs(expected[1]).max() > 0.01  # the spring did couple the pendulums


def test_the_export_satisfies_the_ssp_schema_and_fmpy_reads_it(tmp_path: Path) -> None:
    path = coupled_pendulums(JacobiAlgorithm()).to_ssp(tmp_path / "pendulums.ssp", 0.0, TF,
                                                       DT)
    with zipfile.ZipFile(path) as archive:
        names = set(archive.namelist())
        root = etree.fromstring(archive.read("SystemStructure.ssd"))
    assert names == {"SystemStructure.ssd", "resources/pendulum_cvode.fmu",
                     "resources/torsion_spring.fmu"}  # one copy of the shared FMU
    schema_dir = Path(fmpy_ssd.__file__).parent / "schema"
    schema = etree.XMLSchema(file=str(schema_dir / "SystemStructureDescription.xsd"))
    assert schema.validate(root), schema.error_log

    description = fmpy_ssd.read_ssd(str(path), validate=True)
    assert [e.name for e in description.system.elements] == ["P1", "P2", "Spring"]
    assert len(description.system.connections) == 6
    spring = description.system.elements[2]
    values = {p.name: p.value for p in spring.parameterBindings[0].parameterValues[0].parameters}
    assert values == {"k": "100.0", "d": "1.0"}


def test_an_imported_ssp_exports_again_unchanged(tmp_path: Path) -> None:
    first = coupled_pendulums(JacobiAlgorithm()).to_ssp(tmp_path / "first.ssp", 0.0, TF, DT)
    second = load(first).to_ssp(tmp_path / "second.ssp", 0.0, TF, DT)
    with zipfile.ZipFile(first) as a, zipfile.ZipFile(second) as b:
        assert a.read("SystemStructure.ssd") == b.read("SystemStructure.ssd")


def test_a_system_with_a_python_component_is_refused(tmp_path: Path) -> None:
    from syssimx import TableSource

    system = coupled_pendulums(JacobiAlgorithm())
    signals = np.zeros(2, dtype=[("time", float), ("u", float)])
    signals["time"] = [0.0, 1.0]
    system.add_component(TableSource("table", signals))
    with pytest.raises(SSPError, match="component 'table' is not an FMU; an SSP holds FMU "
                                       "components only"):
        system.to_ssp(tmp_path / "x.ssp")
    assert not (tmp_path / "x.ssp").exists()


def test_events_are_named_when_left_out(tmp_path: Path) -> None:
    from syssimx.ssp import SSPWarning

    system = coupled_pendulums(JacobiAlgorithm())
    system.components["P1"].add_event_indicator("upright", variable="theta", direction=1)
    with pytest.warns(SSPWarning, match=r"SSP 1.0 has no events; not written: event "
                                        r"indicator P1.upright$"):
        system.to_ssp(tmp_path / "x.ssp")
