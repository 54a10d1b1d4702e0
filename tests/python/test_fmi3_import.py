"""FMI 3.0 Co-Simulation import: events an FMU handles itself (early return, event mode), state
rollback, types, String and Binary values, units, and the clear errors for what syssimx does
not run (no interface it runs, String arrays, isolation). Model Exchange is tested in
test_fmi3_model_exchange.py; arrays and 64-bit integers in test_fmi3_arrays.py; String and
Binary ports in test_string_variables.py.

The FMUs are our own FMI 3.0 builds (`<stem>_fmi3`, the same models as the FMI 2.0 ones), the
Reference FMUs built for FMI 3.0 (SYSSIMX_REFERENCE_FMUS or <repository>/../shared/
reference-fmus; those tests are skipped without them), and copies of them with an edited
modelDescription.
"""

from __future__ import annotations

import itertools
import math
import zipfile
from pathlib import Path

import bouncing_ball
import numpy as np
import pendulum_wall
import pytest
from fmpy import simulate_fmu
from reference_root import reference_root
from scipy.special import ellipk
from syssimx import Connection, FMUComponent, System, TableSource, fmus
from syssimx.cli import main
from syssimx.core.port import PortType
from syssimx.errors import ConfigurationError, FMUFileError, SimulationError

# the seed's pendulum: the quarter period from rest at 0.5 rad (tests/python/
# test_hybrid_pendulum.py derives it)
EXACT = ellipk(math.sin(0.5 / 2) ** 2) / math.sqrt(40.0 * 9.81 * 0.6 / 20.0)



FOLDER = reference_root() / "fmi3"
reference = pytest.mark.skipif(not FOLDER.is_dir(), reason=(
    f"the FMI 3.0 Reference FMUs are absent (no folder {FOLDER}): set SYSSIMX_REFERENCE_FMUS "
    "to the folder holding fmi3/"))

BALL = str(FOLDER / "BouncingBall.fmu")
FEEDTHROUGH = str(FOLDER / "Feedthrough.fmu")


def edited(tmp_path: Path, source: str, *replacements: tuple[str, str]) -> str:
    """A copy of the FMU at `source` whose modelDescription has each (old, new) replaced."""
    target = tmp_path / Path(source).name
    with zipfile.ZipFile(source) as original, zipfile.ZipFile(target, "w") as copy:
        for item in original.infolist():
            data = original.read(item.filename)
            if item.filename == "modelDescription.xml":
                text = data.decode()
                for old, new in replacements:
                    assert old in text
                    text = text.replace(old, new)
                data = text.encode()
            copy.writestr(item, data)
    return str(target)


# ------------------------------------------------------------------------------ events
def fmpy_early_returns() -> list[float]:
    """The times FMPy's FMI 3.0 loop returns early at (event mode, early return allowed): its
    samples off the 0.01 grid."""
    result = simulate_fmu(BALL, stop_time=3.0, output_interval=0.01, use_event_mode=True,
                          early_return_allowed=True, output=["h"])
    times = result["time"]
    # FMPy samples an early return twice: before and after its event mode
    return times[np.flatnonzero(np.diff(times) == 0)].tolist()


def ball_system(indicator: bool = False, fmu: str = BALL, **parameters: float
                ) -> tuple[System, FMUComponent]:
    system = System("ball")
    ball = FMUComponent("Ball", fmu)
    ball.set_parameters(**parameters)
    if indicator:  # the apex (v falls through 0): located by rollback
        ball.add_event_indicator("apex", variable="v", direction=-1)
    system.add_component(ball)
    system.initialize(0.0)
    return system, ball


@reference
def test_the_reference_ball_handles_its_bounces_itself_at_fmpys_times_without_rollback():
    system, ball = ball_system()
    result = system.run(0.0, 3.0, 0.01)
    own = [e.t for e in result.events]
    assert {(e.component, e.event, e.own) for e in result.events} == {("Ball", "fmu_event",
                                                                       True)}
    assert own == fmpy_early_returns()
    # The FMU's Euler step of 1e-3 finds each bounce; after its event update it reports the
    # indicator's return from below zero one step later (an event that changes nothing).
    assert own[:4] == [0.453, 0.454, 1.089, 1.09]
    statistics = result.statistics
    assert (statistics.own_events, statistics.events) == (24, 0)
    assert (statistics.state_saves, statistics.state_restores) == (0, 0)
    # one doStep per macro step, one more after each early return inside it (1.09 is on the
    # grid: the step ends there, nothing is left to step)
    inside = [t for t in own if abs(t / 0.01 - round(t / 0.01)) > 1e-9]
    assert len(inside) == 23 and 1.09 not in inside
    assert ball.instance.counters()["do_step"] == 300 + 23
    t, values = result["Ball"]
    assert t.tolist() == pytest.approx(np.linspace(0.0, 3.0, 301).tolist(), abs=1e-12)
    theirs = simulate_fmu(BALL, stop_time=3.0, output_interval=0.01, output=["h", "v"])
    np.testing.assert_array_equal(values["h"], theirs["h"])


@reference
def test_the_reference_balls_own_events_are_recorded_once_under_rollbacks():
    """The apex indicator makes the master restore and re-step the ball around every apex;
    localization trials that cross a bounce report it again, and the restore drops it: each
    bounce is recorded once, at the same times as without the indicator."""
    system, _ = ball_system(indicator=True)
    system.algorithm.tol_time = 1e-9
    result = system.run(0.0, 3.0, 0.01)
    own = [e.t for e in result.events if e.own]
    assert own == fmpy_early_returns()
    apexes = [e.t for e in result.events if e.event == "apex"]
    assert len(apexes) == 12 and apexes[0] == 0.0  # v starts at 0 and falls
    assert result.statistics.state_restores > 100
    # the apex of the first bounce: v = 0 between the bounce at 0.454 and the next
    assert 0.454 < apexes[1] < 1.089


@reference
def test_fmu_state_serializes_and_restores_the_reference_ball():
    """A state taken at 0.2 and serialized brings the ball back there; one doStep of 0.2 from
    it reaches the h the system's twenty steps reached (the same internal Euler steps)."""
    system, ball = ball_system()
    system.run(0.0, 0.2, 0.01)
    frozen = ball.instance.serializeFMUstate(ball.instance.getFMUstate())
    h = ball.value_reference("h")
    at_04 = system.run(0.2, 0.4, 0.01)["Ball"][1]["h"][-1]
    ball.instance.setFMUstate(ball.instance.deserializeFMUstate(frozen))
    assert ball.instance.getReal([h])[0] == system.get_history()["Ball"][1]["h"][20]
    ball.instance.doStep(0.2, 0.2)
    assert ball.instance.getReal([h])[0] == at_04 == pytest.approx(1 - 9.81 * 0.4**2 / 2,
                                                                    abs=3e-3)


def closed_form_bounces(count: int) -> list[float]:
    """Bounce times of a ball dropped from H0 at rest, restitution e: t1, then flights of
    2 v1 e**k / g."""
    t1 = math.sqrt(2 * bouncing_ball.H0 / bouncing_ball.G)
    e = bouncing_ball.RESTITUTION
    return [t1 * (1 + 2 * sum(e**k for k in range(1, n))) for n in range(1, count + 1)]


def our_ball(indicator: bool = False) -> tuple[System, FMUComponent]:
    return ball_system(indicator, fmus.path("bouncing_ball_cvode_fmi3"), h0=bouncing_ball.H0,
                       v0=0.0, g=bouncing_ball.G, e=bouncing_ball.RESTITUTION,
                       cvode_relative_tolerance=1e-12)


def test_our_ball_bounces_at_the_closed_form_times_without_rollback():
    """CVODE's root finder stops the FMI 3.0 ball at the floor, it returns early, syssimx
    handles the bounce in event mode: the closed-form times within 1e-8, no state saved or
    restored (the hybrid algorithm is not even chosen: there is no indicator)."""
    system, ball = our_ball()
    result = system.run(0.0, 3.5, 0.01)
    times = [e.t for e in result.events]
    assert len(times) == 9
    np.testing.assert_allclose(times, closed_form_bounces(9), rtol=0, atol=1e-8)
    assert {(e.component, e.event, e.own) for e in result.events} == {("Ball", "fmu_event",
                                                                       True)}
    statistics = result.statistics
    assert (statistics.own_events, statistics.events) == (9, 0)
    assert (statistics.state_saves, statistics.state_restores) == (0, 0)
    assert ball.instance.counters()["do_step"] == 350 + 9  # one more doStep per bounce
    assert np.all(result["Ball"][1]["h"] >= -1e-9)


def test_our_balls_bounces_are_recorded_once_under_rollbacks():
    """An apex indicator (v falling through 0) on the same ball makes the master roll it back
    and re-step it around every apex, through trials that cross bounces: each bounce is still
    recorded once, at its closed-form time (CVODE restarted at other points finds it within
    1e-10 of where it found it without the indicator)."""
    alone = [e.t for e in our_ball()[0].run(0.0, 3.5, 0.01).events]
    system, _ = our_ball(indicator=True)
    result = system.run(0.0, 3.5, 0.01)
    own = [e.t for e in result.events if e.own]
    np.testing.assert_allclose(own, alone, rtol=0, atol=1e-10)
    np.testing.assert_allclose(own, closed_form_bounces(9), rtol=0, atol=1e-8)
    assert result.statistics.own_events == 9
    apexes = [e.t for e in result.events if e.event == "apex"]
    assert len(apexes) == 9 and result.statistics.state_restores > len(apexes)
    # each apex lies halfway between two bounces (a symmetric flight)
    bounces = closed_form_bounces(9)
    np.testing.assert_allclose(apexes[1:], [(a + b) / 2 for a, b in itertools.pairwise(
        bounces)], rtol=0, atol=1e-8)


def test_the_seed_scenario_with_the_fmi3_pendulum_finds_the_fmi2_event_time():
    """The seed's pendulum against a wall (plain component, indicator in C, reinitializing
    handler) with pendulum_cvode_fmi3: the FMI 2.0 build's event time within tol_time, and the
    same trajectory."""
    fmi2, _ = pendulum_wall.build("cvode")
    fmi3, pendulum = pendulum_wall.build("cvode_fmi3")
    pendulum.set_parameters(cvode_relative_tolerance=1e-10)  # build() sets it for "cvode" only
    fmi3.initialize(0.0)
    ours, theirs = fmi3.run(0.0, 1.0, 0.05), fmi2.run(0.0, 1.0, 0.05)
    assert [e.event for e in ours.events] == ["wall_hit"]
    assert abs(ours.events[0].t - theirs.events[0].t) <= fmi3.algorithm.tol_time
    assert abs(ours.events[0].t - EXACT) < 1e-8
    np.testing.assert_allclose(ours["P"][1]["theta"], theirs["P"][1]["theta"], rtol=0,
                               atol=1e-12)
    assert ours.statistics.state_restores == theirs.statistics.state_restores > 0


def test_an_fmi3_loop_is_solved_with_fmi3_directional_derivatives():
    """The gain/sum loop of test_loop_jacobian.py (y = a u in m, y = b - c u with u in cm)
    with the FMI 3.0 builds: Newton's columns come from fmi3GetDirectionalDerivative, and
    every sample satisfies the loop like the FMI 2.0 builds' does."""
    a, b, c = 1.5, 2.0, 0.02
    results = {}
    for suffix in ("", "_fmi3"):
        gain = FMUComponent("Gain", fmus.path(f"gain{suffix}"))
        gain.set_parameters(k=a)
        summer = FMUComponent("Sum", fmus.path(f"sum{suffix}"))
        summer.set_parameters(b=b, c=c)
        system = System("loop")
        system.add_component(gain)
        system.add_component(summer)
        system.add_connection(Connection("Gain", "y", "Sum", "u"))
        system.add_connection(Connection("Sum", "y", "Gain", "u"))
        system.initialize(0.0)
        results[suffix] = (system.run(0.0, 1.0, 0.1), gain.instance.counters())
    result, counters = results["_fmi3"]
    np.testing.assert_allclose(result["Sum"][1]["y"], b / (1 + 100 * a * c), rtol=0,
                               atol=1e-10)
    statistics = result.statistics
    assert statistics.directional_derivatives == 2 * statistics.loop_iterations >= 2
    assert counters["directional_derivative"] == statistics.loop_iterations
    fmi2 = results[""][0]
    assert statistics.loop_iterations == fmi2.statistics.loop_iterations
    np.testing.assert_array_equal(result["Gain"][1]["y"], fmi2["Gain"][1]["y"])


# ------------------------------------------------------------------------------ values
@reference
def test_units_come_from_the_unit_definitions():
    ball = FMUComponent("Ball", BALL)
    assert (ball.output_specs["h"].unit, ball.output_specs["v"].unit) == ("m", "m/s")
    assert ball.info.parameters["g"].unit == "m/s2"
    assert ball.info.parameters["e"].unit is None


@reference
def test_model_structure_gives_the_direct_feedthrough():
    feedthrough = FMUComponent("F", FEEDTHROUGH)
    assert feedthrough.direct_feedthrough["Float32_continuous_output"] == {
        "Float32_continuous_input"}
    assert feedthrough.direct_feedthrough["Int64_output"] == {"Int64_input"}
    assert FMUComponent("Ball", BALL).direct_feedthrough == {"h": set(), "v": set(),
                                                             "h_ft": set()}


@reference
def test_strings_and_binaries_are_set_as_parameters_and_read_back():
    system = System("texts")
    feedthrough = FMUComponent("F", FEEDTHROUGH)
    system.add_component(feedthrough)
    assert feedthrough.parameters["String_input"] == "Set me!"
    assert feedthrough.parameters["Binary_input"] == b"foo"
    feedthrough.set_parameters(String_input="grüße", Binary_input=b"\x00\xff")
    system.initialize(0.0)
    system.run(0.0, 0.2, 0.1)
    state = feedthrough.get_state()
    assert state["String_output"]["value"] == "grüße"
    assert state["Binary_output"]["value"] == b"\x00\xff"
    with pytest.raises(ConfigurationError) as info:
        feedthrough.set_parameters(Binary_input="00ff")
    assert str(info.value) == "F.Binary_input is Binary; got str '00ff'"


def driven(column: str, value: int) -> System:
    """The Feedthrough with `column` driven to 0, then to `value` from t = 0.5."""
    signals = np.array([(0.0, 0), (0.5, value)], dtype=[("time", np.float64),
                                                        (column, np.int64)])
    system = System("driven")
    system.add_component(FMUComponent("F", FEEDTHROUGH))
    system.add_component(TableSource("u", signals))
    system.add_connection(Connection("u", column, "F", column))
    system.initialize(0.0)
    return system


@reference
def test_an_integer_beyond_the_variables_type_names_the_variable():
    system = driven("UInt8_input", -1)
    with pytest.raises(SimulationError) as info:
        system.run(0.0, 1.0, 0.1)
    assert "variable 'UInt8_input' (UInt8) cannot take -1: outside 0..255" in str(info.value)
    assert system.get_history()["F"][0][-1] == pytest.approx(0.5)  # the samples before stay


@reference
def test_an_integer_beyond_the_engines_ports_names_the_input():
    """UInt32, Int64 and UInt64 travel as Real ports: exact up to 2**53, beyond refused by the
    back-end naming the variable; an Enumeration (Int64 in FMI 3.0) stays an Integer port."""
    with pytest.raises(SimulationError) as info:
        driven("Int64_input", 2**53 + 2).run(0.0, 1.0, 0.1)
    assert str(info.value).endswith(
        "fmi3SetFloat64 refused at t=0.5: variable 'Int64_input' (Int64) cannot take "
        "9007199254740994: outside -9007199254740992..9007199254740992 (its range, within the "
        "2^53 up to which the engine's Real ports carry integers exactly)")
    feedthrough = FMUComponent("G", FEEDTHROUGH)
    assert [feedthrough.input_specs[n].type for n in ("Int32_input", "UInt32_input",
                                                      "UInt64_input", "Enumeration_input")] \
        == [PortType.INT, PortType.REAL, PortType.REAL, PortType.INT]
    feedthrough.set_inputs({"UInt32_input": 2**32 - 1, "Int64_input": -(2**53)})
    system = System("wide")
    system.add_component(feedthrough)
    system.initialize(0.0)
    _, values = system.run(0.0, 0.2, 0.1)["G"]
    assert values["UInt32_output"][-1] == 2**32 - 1 and values["Int64_output"][-1] == -(2**53)


@reference
def test_info_shows_fmi3_capabilities_and_display_units(capsys: pytest.CaptureFixture[str]):
    assert main(["info", BALL]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert "FMI version:      3.0" in lines
    assert "  hasEventMode                             yes" in lines
    assert "  canReturnEarlyAfterIntermediateUpdate    yes" in lines
    alias = next(line for line in lines if line.split()[:1] == ["h_ft"])
    assert alias.split()[1:6] == ["output", "continuous", "Float64", "m", "(display"]


# ------------------------------------------------------------------------------ refusals
@reference
def test_scheduled_execution_only_is_refused_naming_the_file(tmp_path: Path):
    path = edited(tmp_path, BALL, ("<CoSimulation", "<!--CoSimulation"),
                  ('hasEventMode="true"/>', 'hasEventMode="true"-->'),
                  ("<ModelExchange", "<!--ModelExchange"),
                  ('canSerializeFMUState="true"/>', 'canSerializeFMUState="true"-->'))
    with pytest.raises(FMUFileError) as info:
        FMUComponent("Ball", path)
    assert str(info.value) == (f"{path}: the FMI 3.0 description declares neither "
                               "CoSimulation nor ModelExchange")


@reference
def test_a_string_array_is_refused_naming_the_variable(tmp_path: Path):
    path = edited(tmp_path, FEEDTHROUGH, ('<String name="String_input" valueReference="29" '
                                          'causality="input">',
                                          '<String name="String_input" valueReference="29" '
                                          'causality="input"><Dimension start="1"/>'))
    with pytest.raises(FMUFileError) as info:
        FMUComponent("F", path)
    assert str(info.value) == (f"{path}: variable 'String_input' is a String array (input): "
                               "String and Binary arrays are not supported (numeric and "
                               "Boolean arrays are)")


@reference
def test_isolation_is_refused_for_fmi3():
    with pytest.raises(ConfigurationError) as info:
        FMUComponent("Ball", BALL, isolated=True)
    assert str(info.value) == (f"component 'Ball': isolated=True is not supported for FMI 3.0 "
                               f"FMUs ({BALL}): the FMU host process speaks FMI 2.0 and "
                               "FMI 1.0 Co-Simulation only")
