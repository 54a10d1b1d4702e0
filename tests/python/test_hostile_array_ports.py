"""FMI 3.0 arrays of many elements are cheap to open (issue 20, item 3): an array is one
record, and an element's spec, port, start, parameter and value reference are made when they
are asked for. Before: one Python port per element, 12.5 s and 137 MB for 10**5 elements.

The FMU is gain_fmi3 with a Float64 input array `a` of 50 000 elements and a 200 x 200 Int32
parameter `p`, both with start values (its binary never sees them: nothing here runs it)."""

from __future__ import annotations

import tracemalloc
import zipfile
from pathlib import Path

import pytest
from syssimx import FMUComponent, fmus
from syssimx.core.port import PortType
from syssimx.fmu.info import read_fmu

INPUTS, SIDE = 50_000, 200
ARRAYS = (
    '<Float64 name="a" valueReference="4" causality="input" variability="continuous" '
    'start="{a}"><Dimension start="' + str(INPUTS) + '"/></Float64>'
    '<Int32 name="p" valueReference="5" causality="parameter" variability="tunable" '
    'start="{p}"><Dimension start="' + str(SIDE) + '"/><Dimension start="' + str(SIDE) +
    '"/></Int32>')


def a_start(position: int) -> float:
    return position * 0.5


def p_start(position: int) -> int:
    return position % 1000 - 500


@pytest.fixture(scope="module")
def large_fmu(tmp_path_factory: pytest.TempPathFactory) -> str:
    with zipfile.ZipFile(fmus.path("gain_fmi3")) as gain:
        entries = {name: gain.read(name) for name in gain.namelist()}
    text = entries["modelDescription.xml"].decode()
    arrays = ARRAYS.format(a=" ".join(repr(a_start(i)) for i in range(INPUTS)),
                           p=" ".join(str(p_start(i)) for i in range(SIDE * SIDE)))
    entries["modelDescription.xml"] = text.replace("</ModelVariables>",
                                                   arrays + "</ModelVariables>").encode()
    path = tmp_path_factory.mktemp("arrays") / "large_arrays.fmu"
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in entries.items():
            archive.writestr(name, data)
    return str(path)


def test_opening_makes_no_object_per_element(large_fmu: str):
    """The old code held about 1.3 kB per element after opening (ports, specs, starts,
    parameters, value references, element variables): over 100 MB here. The start values
    alone are 0.7 MB as numpy arrays."""
    read_fmu(large_fmu)  # the first read's imports (fmpy, lxml) are not the FMU's
    Path(large_fmu).touch()  # read again below: the cache keys on the file's mtime
    tracemalloc.start()
    try:
        component = FMUComponent("G", large_fmu)
        held, _ = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert held < 8 * 2**20, f"{held / 2**20:.1f} MiB held after opening"
    assert len(component.inputs) == INPUTS + 1
    assert len(component.info.parameters) == SIDE * SIDE + 1
    # made so far: the scalars' only
    assert list(component.inputs.made()) == ["u"]
    assert list(component.input_specs.made()) == ["u"]
    assert list(component.parameters.made()) == ["k"]
    assert list(component.info.variables.made()) == ["y", "u", "k", "time"]


def test_an_element_asked_for_is_made_as_a_scalar_port_was(large_fmu: str):
    component = FMUComponent("G", large_fmu)
    port = component.inputs["a[49999]"]
    assert port.spec.name == "a[49999]" and port.spec.type == PortType.REAL
    assert port.spec.unit is None and port.spec.direction == "in"
    assert port.raw() == a_start(49999)
    assert component.inputs["a[49999]"] is port  # made once
    assert component.input_specs["a[7]"].type == PortType.REAL
    parameter = component.info.parameters["p[199,3]"]
    assert parameter.type == PortType.INT and parameter.tunable
    assert parameter.start == p_start(199 * SIDE + 3)
    assert component.parameters["p[1,2]"] == p_start(SIDE + 2)
    first = component.value_reference("a[0]")
    assert first > 5 and component.value_reference("a[3]") == first + 3
    assert component.value_reference("p[0,0]") == first + INPUTS
    assert list(component.inputs)[:3] == ["u", "a[0]", "a[1]"]
    assert list(component.info.parameters)[:3] == ["k", "p[0,0]", "p[0,1]"]
    for name in ("a[50000]", "a[01]", "a[-1]", "a[1,2]", "a", "p[200,0]", "p[3]", "a[ 1]",
                 "a[\u0661]"):  # an Arabic-Indic digit one, which int() would read
        assert name not in component.inputs and name not in component.info.parameters, name
        with pytest.raises(KeyError):
            component.inputs[name]
    assert component.direct_feedthrough["y"] == {"u"}
    assert len(component.inputs.made()) == 2


def test_only_the_elements_set_are_written(large_fmu: str):
    component = FMUComponent("G", large_fmu)
    component.set_parameters(**{"p[1,2]": 5})
    assert component.user_parameters() == {"p[1,2]": 5}
    assert component.get_default_parameters()["p[1,2]"] == p_start(SIDE + 2)
    component.set_inputs({"a[3]": 2.5})
    assert component.inputs["a[3]"].raw() == 2.5 and component.input_start("a[3]") == 2.5
