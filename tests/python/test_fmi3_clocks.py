"""FMI 3.0 clocks as read from a description (syssimx.fmu.clocks): the Reference FMUs'
Clocks.fmu (Scheduled Execution) and copies of Feedthrough.fmu with a Clock added, and the
refusals that name the clock.

The Reference FMUs are found as in test_fmi3_import.py (SYSSIMX_REFERENCE_FMUS or
<repository>/../shared/reference-fmus); these tests are skipped without them.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from reference_root import reference_root
from syssimx import FMUComponent
from syssimx.errors import FMUFileError
from syssimx.fmu.clocks import ClockInfo
from syssimx.fmu.description_fmi3 import clock_structure
from test_fmi3_import import edited

FOLDER = reference_root() / "fmi3"
pytestmark = pytest.mark.skipif(not FOLDER.is_dir(), reason=(
    f"the FMI 3.0 Reference FMUs are absent (no folder {FOLDER}): set SYSSIMX_REFERENCE_FMUS "
    "to the folder holding fmi3/"))
CLOCKS = FOLDER / "Clocks.fmu"
FEEDTHROUGH = str(FOLDER / "Feedthrough.fmu")
# a Clock added to Feedthrough.fmu, clocking its Int32 output
_ADDED_CLOCK = ('<Int32 name="Int32_output" valueReference="20" causality="output"',
                '<Clock name="tick" valueReference="9001" causality="input" '
                'intervalVariability="fixed" intervalDecimal="0.25" shiftDecimal="0.5" '
                'priority="3" supportsFraction="true"/>'
                '<Int32 name="Int32_output" valueReference="20" causality="output" '
                'clocks="9001"')


def test_the_clocks_of_clocks_fmu_are_read_as_declared():
    clocks = clock_structure(CLOCKS).clocks
    assert clocks == (
        ClockInfo("inClock1", 1001, "input", "constant", interval=1.0, priority=0),
        ClockInfo("inClock2", 1002, "input", "triggered", priority=1),
        ClockInfo("inClock3", 1003, "input", "countdown", priority=2, clocks=(1001,)),
        ClockInfo("outClock", 1005, "output", "triggered", clocks=(1001, 1002, 1003)))
    assert [clock.period for clock in clocks] == [1.0, None, None, None]


def test_the_clocked_variables_and_clock_dependencies_of_clocks_fmu():
    structure = clock_structure(CLOCKS)
    assert structure.clocked_variables == {
        "inClock1Ticks": (1001,), "inClock2Ticks": (1002,),
        "totalInClockTicks": (1001, 1002, 1003), "result2": (1002,), "output3": (1003,)}
    # every ModelStructure unknown that is clocked or depends on a clock; inClock3Ticks (2003)
    # is clocked by no attribute but depends on inClock3
    assert structure.dependencies == {1005: (1001, 1002, 1003), 2001: (1001,),
                                      2002: (1002,), 2003: (1003,), 2004: (1001, 1002, 1003),
                                      2005: (1002, 2006), 2007: (1003,)}
    assert structure.clocked_states == ()
    assert structure.by_name("inClock3").interval_variability == "countdown"


def test_clocks_fmu_is_refused_as_a_co_simulation_component_naming_its_interface():
    with pytest.raises(FMUFileError) as info:
        FMUComponent("C", str(CLOCKS))
    assert str(info.value) == (f"{CLOCKS}: FMI 3.0 Scheduled Execution is not supported as a "
                               "Co-Simulation or Model Exchange component (syssimx runs FMI "
                               "3.0 Co-Simulation and Model Exchange FMUs without clocks)")


def test_a_co_simulation_fmu_with_a_clock_is_read_and_refused_naming_the_clock(tmp_path: Path):
    path = edited(tmp_path, FEEDTHROUGH, _ADDED_CLOCK)
    structure = clock_structure(Path(path))
    assert structure.clocks == (ClockInfo("tick", 9001, "input", "fixed", interval=0.25,
                                          shift=0.5, priority=3, supports_fraction=True),)
    assert structure.clocked_variables == {"Int32_output": (9001,)}
    # periodic, triggered, countdown and tunable input clocks are ticked by the engine; a
    # local one is refused
    (tmp_path / "triggered").mkdir()
    triggered = edited(tmp_path / "triggered", FEEDTHROUGH, (_ADDED_CLOCK[0], _ADDED_CLOCK[1]
                       .replace('intervalVariability="fixed" intervalDecimal="0.25" '
                                'shiftDecimal="0.5" ', 'intervalVariability="triggered" ')))
    assert FMUComponent("F", triggered).triggered_clocks == ["tick"]
    (tmp_path / "tunable").mkdir()
    tunable = edited(tmp_path / "tunable", FEEDTHROUGH, (_ADDED_CLOCK[0], _ADDED_CLOCK[1]
                     .replace('intervalVariability="fixed"', 'intervalVariability="tunable"')))
    assert FMUComponent("F", tunable).info.clocks.by_name("tick").interval_variability == \
        "tunable"
    (tmp_path / "local").mkdir()
    local = edited(tmp_path / "local", FEEDTHROUGH, (_ADDED_CLOCK[0], _ADDED_CLOCK[1]
                   .replace('causality="input"', 'causality="local"')))
    with pytest.raises(FMUFileError) as info:
        FMUComponent("F", local)
    assert str(info.value) == (f"{local}: Clock 'tick' (local, intervalVariability fixed) is "
                               "not supported: a local clock is the FMU's own")


def test_counters_and_resolution_give_the_period_and_first_tick(tmp_path: Path):
    path = edited(tmp_path, FEEDTHROUGH, (
        _ADDED_CLOCK[0], _ADDED_CLOCK[1].replace(
            'intervalDecimal="0.25" shiftDecimal="0.5"',
            'intervalCounter="3" shiftCounter="2" resolution="4"')))
    clock = clock_structure(Path(path)).by_name("tick")
    assert (clock.period, clock.first_tick) == (0.75, 0.5)


@pytest.mark.parametrize(("old", "new", "message"), [
    ('intervalVariability="fixed"', 'intervalVariability="sometimes"',
     "Clock 'tick' has intervalVariability 'sometimes'; FMI 3.0 allows constant, fixed, "
     "tunable, changing, countdown, triggered"),
    ('intervalDecimal="0.25"', 'intervalDecimal="0"',
     "Clock 'tick' has intervalDecimal='0'; it is a positive number of seconds"),
    ('intervalDecimal="0.25"', 'intervalDecimal="nan"',
     "Clock 'tick' has intervalDecimal='nan'; it is a positive number of seconds"),
    ('priority="3"', 'priority="-1"',
     "Clock 'tick' has priority='-1'; it is a whole number 0 or more"),
    ('clocks="9001"', 'clocks="9002"',
     "variable 'Int32_output' is clocked by value reference 9002, which is no Clock"),
])
def test_a_malformed_clock_is_refused_naming_it(tmp_path: Path, old: str, new: str,
                                                message: str):
    path = edited(tmp_path, FEEDTHROUGH, (_ADDED_CLOCK[0], _ADDED_CLOCK[1].replace(old, new)))
    with pytest.raises(FMUFileError) as info:
        clock_structure(Path(path))
    assert str(info.value) == f"{path}: {message}"
