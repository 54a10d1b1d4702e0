"""FMI 3.0 arrays and 64-bit integers through syssimx, against FMPy.

The FMU (tests/fmus/fmi3_arrays, built by meson beside the tests) has a Float64 input u[3],
a tunable Float64 parameter k[3] and an output y = k * u, a Boolean output positive[3] = y > 0,
all sized by the structural parameter n; a 2x2 Int32 parameter m sized by its dimensions'
starts with an output order = 10 * m[0,1] + m[1,0]; an Int64 output big = 2**32 + the steps
done; writes, the number of fmi3SetFloat64 calls that wrote u; and a UInt64 output
wide = 2**40 * |u[0]|.

Each element is a port named as FMPy names elements (0-based, row-major: "u[0]", "m[0,1]");
the back-end reads and writes each array whole, with one call.
"""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np
import pytest
from fmpy import simulate_fmu
from syssimx import Connection, FMUComponent, GaussSeidelAlgorithm, System, TableSource
from syssimx._paths import build_dir
from syssimx.core.port import PortType
from syssimx.errors import ConfigurationError, FMUFileError, SimulationError

ROOT = Path(__file__).resolve().parents[2]
ELEMENTS = ["u[0]", "u[1]", "u[2]"]
# u steps at t = 0.5; FMPy and the TableSource hold each value until the next row
TIMES = [0.0, 0.5, 0.5, 1.0]
U = [(1.0, -2.0, 0.5), (1.0, -2.0, 0.5), (3.0, 4.0, -1.0), (3.0, 4.0, -1.0)]
K = (2.0, 0.5, -1.0)


@pytest.fixture(scope="module")
def arrays_fmu() -> str:
    build = build_dir() or ROOT / "build" / "release"
    path = build / "tests" / "fmus" / "fmi3_arrays" / "fmi3_arrays.fmu"
    if not path.is_file():
        pytest.skip(f"the FMI 3.0 arrays test FMU is not built ({path} is missing): run "
                    "meson compile")
    return str(path)


def fmpy_signals() -> np.ndarray:
    return np.array(list(zip(TIMES, U, strict=True)),
                    dtype=[("time", np.float64), ("u", np.float64, (3,))])


def element_signals() -> np.ndarray:
    return np.array([(t, *u) for t, u in zip(TIMES, U, strict=True)],
                    dtype=[("time", np.float64), *((name, np.float64) for name in ELEMENTS)])


def driven_system(path: str) -> tuple[System, FMUComponent]:
    arrays = FMUComponent("A", path)
    arrays.set_parameters(**{f"k[{i}]": k for i, k in enumerate(K)})
    system = System("arrays")
    system.add_component(arrays)
    system.add_component(TableSource("u", element_signals(), hold=ELEMENTS))
    for name in ELEMENTS:
        system.add_connection(Connection("u", name, "A", name))
    system.initialize(0.0)
    return system, arrays


def test_each_element_is_a_port_named_as_fmpy_names_it(arrays_fmu: str):
    arrays = FMUComponent("A", arrays_fmu)
    assert list(arrays.input_specs) == ELEMENTS
    assert list(arrays.output_specs) == ["y[0]", "y[1]", "y[2]", "big", "order",
                                         "positive[0]", "positive[1]", "positive[2]", "writes",
                                         "wide"]
    assert list(arrays.info.parameters) == ["k[0]", "k[1]", "k[2]", "m[0,0]", "m[0,1]",
                                            "m[1,0]", "m[1,1]"]
    assert [arrays.info.parameters[f"k[{i}]"].start for i in range(3)] == [1.0, 2.0, 3.0]
    assert arrays.output_specs["big"].type == PortType.REAL  # an Int64: exact to 2**53
    assert arrays.info.feedthrough["y[1]"] == set(ELEMENTS)
    assert arrays.info.feedthrough["big"] == set()


def test_a_system_equals_fmpy_element_by_element(arrays_fmu: str):
    system, _ = driven_system(arrays_fmu)
    t, ours = system.run(0.0, 1.0, 0.1)["A"]
    theirs = simulate_fmu(arrays_fmu, stop_time=1.0, output_interval=0.1, input=fmpy_signals(),
                          start_values={"k": list(K)},
                          output=["y", "positive", "big", "order", "wide"])
    np.testing.assert_array_equal(t, theirs["time"])
    for i in range(3):
        np.testing.assert_array_equal(ours[f"y[{i}]"], theirs["y"][:, i], err_msg=f"y[{i}]")
        np.testing.assert_array_equal(ours[f"positive[{i}]"], theirs["positive"][:, i],
                                      err_msg=f"positive[{i}]")
    np.testing.assert_array_equal(ours["big"], theirs["big"])
    np.testing.assert_array_equal(ours["order"], theirs["order"])
    np.testing.assert_array_equal(ours["wide"], theirs["wide"])
    assert ours["wide"][-1] == 3 * 2**40 and ours["big"][-1] == 2**32 + 10
    assert list(ours["y[1]"][[0, -1]]) == [-1.0, 2.0]


def test_an_array_is_written_with_one_call_per_write(arrays_fmu: str):
    """The engine writes an input when its value changes: the three elements of u, changing
    together at t = 0.5, reach the FMU in one fmi3SetFloat64 call (the FMU refuses a call
    that does not give all three values). writes counts the calls."""
    system, _ = driven_system(arrays_fmu)
    _, values = system.run(0.0, 1.0, 0.1)["A"]
    assert list(values["writes"]) == [2] * 6 + [3] * 5


def test_parameters_of_a_two_dimensional_array_are_row_major(arrays_fmu: str):
    arrays = FMUComponent("A", arrays_fmu)
    arrays.set_parameters(**{"m[0,1]": 5, "m[1,0]": 7})
    system = System("matrix")
    system.add_component(arrays)
    system.initialize(0.0)
    _, ours = system.run(0.0, 0.2, 0.1)["A"]
    theirs = simulate_fmu(arrays_fmu, stop_time=0.2, output_interval=0.1,
                          start_values={"m": [1, 5, 7, 4]}, output=["order"])
    np.testing.assert_array_equal(ours["order"], theirs["order"])
    assert list(ours["order"]) == [57, 57, 57]


def test_an_input_element_set_alone_keeps_the_others_start_values(arrays_fmu: str):
    arrays = FMUComponent("A", arrays_fmu)
    arrays.set_inputs({"u[1]": 5.0})
    system = System("one element")
    system.add_component(arrays)
    system.initialize(0.0)
    _, values = system.run(0.0, 0.1, 0.1)["A"]
    assert [values[f"y[{i}]"][-1] for i in range(3)] == [0.0, 10.0, 0.0]


def test_array_elements_connect_between_two_fmus(arrays_fmu: str):
    """A.y -> B.u element by element, crossed: B.u[i] = A.y[2 - i]. B's output at each point
    is kB times A's output at the point before, as the same chain of scalar gain FMUs records
    it: the engine's sampling, not the arrays'. At t0 it is kB times A's output at t0, the
    input B was given in initialization mode."""
    system, _ = driven_system(arrays_fmu)
    second = FMUComponent("B", arrays_fmu)
    system.add_component(second)
    for i in range(3):
        system.add_connection(Connection("A", f"y[{i}]", "B", f"u[{2 - i}]"))
    system.set_algorithm(GaussSeidelAlgorithm())
    system.initialize(0.0)
    results = system.run(0.0, 1.0, 0.1)
    _, a = results["A"]
    _, b = results["B"]
    for i in range(3):
        np.testing.assert_array_equal(b[f"y[{2 - i}]"][1:], (3 - i) * a[f"y[{i}]"][:-1])
        assert b[f"y[{2 - i}]"][0] == (3 - i) * a[f"y[{i}]"][0]
    assert [b[f"y[{i}]"][-1] for i in range(3)] == [1.0, 4.0, 18.0]


def test_a_structural_parameter_cannot_change(arrays_fmu: str):
    arrays = FMUComponent("A", arrays_fmu)
    with pytest.raises(ConfigurationError) as info:
        arrays.set_parameters(n=4)
    assert str(info.value) == ("component 'A': 'n' is a structural parameter (it sizes the "
                               "array(s) 'u', 'k', 'y', 'positive'); syssimx keeps its start "
                               "value 3: changing it is not supported")


def edited(source: str, target: Path, old: bytes, new: bytes) -> str:
    """A copy of the FMU at `source` whose modelDescription has `old` replaced by `new`."""
    with zipfile.ZipFile(source) as original, zipfile.ZipFile(target, "w") as copy:
        for item in original.infolist():
            data = original.read(item.filename)
            if item.filename == "modelDescription.xml":
                assert old in data
                data = data.replace(old, new)
            copy.writestr(item, data)
    return str(target)


def test_start_values_that_do_not_fill_the_array_are_refused(arrays_fmu: str,
                                                             tmp_path: Path):
    path = edited(arrays_fmu, tmp_path / "short_start.fmu", b'start="1 2 3"', b'start="1 2"')
    with pytest.raises(FMUFileError) as info:
        FMUComponent("A", path)
    assert str(info.value) == f"{path}: array 'k' has 3 elements but 2 start values"


def test_array_ports_take_no_directional_derivatives(arrays_fmu: str, tmp_path: Path):
    """The engine's element references are not the FMU's: an FMU with array ports that
    provides directional derivatives gets finite differences in loops instead."""
    path = edited(arrays_fmu, tmp_path / "derivatives.fmu", b'modelIdentifier="fmi3_arrays"',
                  b'modelIdentifier="fmi3_arrays" providesDirectionalDerivatives="true"')
    assert FMUComponent("A", path).fmu_interface.provides_directional_derivative is False


def test_a_64_bit_output_beyond_2_53_names_the_variable(arrays_fmu: str):
    """wide = 2**40 * |u[0]| is read exactly up to 2**53 (u[0] = 2**13) and refused beyond,
    naming it; the samples before stay readable."""
    arrays = FMUComponent("A", arrays_fmu)
    signals = np.array([(0.0, 2.0**13), (0.5, 2.0**13 + 1)],
                       dtype=[("time", np.float64), ("u[0]", np.float64)])
    system = System("wide")
    system.add_component(arrays)
    system.add_component(TableSource("u", signals, hold=["u[0]"]))
    system.add_connection(Connection("u", "u[0]", "A", "u[0]"))
    system.initialize(0.0)
    with pytest.raises(SimulationError) as info:
        system.run(0.0, 1.0, 0.1)
    assert str(info.value).endswith(
        "fmi3GetFloat64 refused at t=0.60000000000000009: variable 'wide' (UInt64) holds "
        "9008298766368768, beyond 2^53, the largest magnitude up to which the engine's Real "
        "ports carry integers exactly")
    t, values = system.get_history()["A"]
    assert list(values["wide"]) == [2**53] * 6 and t[-1] == pytest.approx(0.5)
