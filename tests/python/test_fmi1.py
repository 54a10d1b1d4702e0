"""FMI 1.0 FMUs run behind the same component: libcosim's identity.fmu (FMI 1.0 Co-Simulation,
ViProMa's demo FMU) gives FMPy's numbers on the same grid; its description is read by the
engine's reader; an FMI 1.0 FMU cannot roll back, which is a clear error at initialize."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from fmpy import simulate_fmu
from samples_root import samples_root
from syssimx import Connection, FMUComponent, JacobiAlgorithm, System, TableSource
from syssimx.errors import ConfigurationError

SIGNALS = np.array([(0.0, 0.5, 1, False), (0.25, -1.5, 4, True), (0.55, 2.25, -3, False),
                    (1.0, 8.0, 11, True)],
                   dtype=[("time", np.float64), ("realIn", np.float64),
                          ("integerIn", np.int32), ("booleanIn", np.bool_)])


def identity() -> Path:
    path = samples_root() / "libcosim" / "fmi1" / "identity.fmu"
    if not path.is_file():
        pytest.skip(f"libcosim's FMI 1.0 identity.fmu is absent ({path}): set "
                    "SYSSIMX_SSP_SAMPLES")
    return path


def test_identity_is_read_as_fmi1_cosimulation():
    component = FMUComponent("I", identity())
    assert component.info.standard.name == "FMI 1.0"
    assert component.fmu_interface.name == "co-simulation"
    assert component.fmu_interface.model_identifier == "identity"
    assert not component.can_get_set_state  # FMI 1.0 has no FMU state
    assert {n: s.type.name for n, s in component.input_specs.items()} == {
        "realIn": "REAL", "integerIn": "INT", "booleanIn": "BOOL"}
    assert sorted(component.output_specs) == ["booleanOut", "integerOut", "realOut"]
    # no ModelStructure in FMI 1.0: every output depends on every input
    assert component.direct_feedthrough["realOut"] == {"realIn", "integerIn", "booleanIn"}


def test_identity_driven_by_a_table_equals_fmpy():
    """The table drives the identity's discrete inputs (held, as FMPy holds discrete inputs)
    in a Jacobi system: each step starts from the table at its start, as FMPy's input does."""
    path = identity()
    system = System("driven")
    system.add_component(TableSource("u", SIGNALS, hold=["realIn"]))
    system.add_component(FMUComponent("I", path))
    for kind in ("real", "integer", "boolean"):
        system.add_connection(Connection("u", f"{kind}In", "I", f"{kind}In"))
    system.set_algorithm(JacobiAlgorithm())
    system.initialize(0.0)
    t, values = system.run(0.0, 1.2, 0.05)["I"]
    reference = simulate_fmu(str(path), stop_time=1.2, output_interval=0.05, input=SIGNALS,
                             output=["realOut", "integerOut", "booleanOut"])
    np.testing.assert_allclose(t, reference["time"], rtol=0, atol=1e-12)  # FMPy sums steps
    for port in ("realOut", "integerOut", "booleanOut"):
        np.testing.assert_array_equal(values[port], reference[port], err_msg=port)
    assert len(set(values["realOut"].tolist())) == 4  # every row of the table came through


def test_set_inputs_reach_an_fmi1_slave_at_once():
    component = FMUComponent("I", identity())
    component.initialize(0.0)
    component.set_inputs({"realIn": 3.5, "integerIn": -2, "booleanIn": True})
    component.do_step(0.0, 0.1)
    assert component.get_state()["realOut"]["value"] == 3.5
    assert component.get_state()["integerOut"]["value"] == -2
    assert component.get_state()["booleanOut"]["value"] is True


def test_event_indicators_on_an_fmi1_fmu_are_refused_at_initialize():
    component = FMUComponent("I", identity())
    component.add_event_indicator("crossing", variable="realOut", direction=1)
    system = System("hybrid")
    system.add_component(component)
    with pytest.raises(ConfigurationError, match=r"^'I' cannot roll back, which locating "
                       r"events needs \(the system has event indicators\): identity\.fmu is an "
                       r"FMI 1\.0 FMU, and FMI 1\.0 has no FMU state to save and restore$"):
        system.initialize(0.0)


def test_an_fmi1_fmu_beside_a_master_indicator_is_refused_at_initialize():
    ramp = np.array([(0.0, -1.0), (1.0, 1.0)], dtype=[("time", np.float64), ("u", np.float64)])
    table = TableSource("src", ramp)
    table.add_event_indicator("zero", variable="u", direction=1)
    system = System("hybrid")
    system.add_component(table)
    system.add_component(FMUComponent("I", identity()))
    with pytest.raises(ConfigurationError, match=r"'I' cannot roll back.*FMI 1\.0 has no FMU "
                       "state"):
        system.initialize(0.0)


def test_isolation_is_refused_for_fmi1():
    with pytest.raises(ConfigurationError, match=r"isolated=True is not supported for FMI 1\.0 "
                       "FMUs"):
        FMUComponent("I", identity(), isolated=True)


def test_cli_simulate_and_info_accept_fmi1(tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    from syssimx.cli import main

    path = str(identity())
    output = tmp_path / "out.csv"
    assert main(["simulate", path, "--stop-time", "0.3", "--step-size", "0.1",
                 "--set", "realIn=2.5", "--set", "integerIn=4", "-o", str(output)]) == 0
    rows = output.read_text().splitlines()
    assert rows[0].split(",")[:3] == ["time", "realOut", "integerOut"]
    assert [row.split(",")[1:3] for row in rows[1:]] == [["2.5", "4"]] * 4
    assert main(["info", path]) == 0
    assert "FMI version:      1.0" in capsys.readouterr().out
