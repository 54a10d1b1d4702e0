"""The data-flow analysis: zero-delay graph, loops, generations and the engine schedule."""

from __future__ import annotations

from pathlib import Path

import pytest
from fmpy import read_model_description
from syssimx.graph.analysis import analyze, feedthrough_from_model_description

NO_FEEDTHROUGH = {"y": set()}
FEEDTHROUGH = {"y": {"u"}}


def test_chain_of_zero_delay_links_runs_in_data_flow_order() -> None:
    # Added in reverse, so insertion order alone would get it wrong. C's output closes the
    # circle through A, which has no feedthrough: no loop.
    components = {"C": FEEDTHROUGH, "B": FEEDTHROUGH, "A": NO_FEEDTHROUGH}
    connections = [("A", "y", "B", "u"), ("B", "y", "C", "u"), ("C", "y", "A", "u")]
    analysis = analyze(components, connections)
    assert analysis.generations == [["A"], ["B"], ["C"]]
    assert analysis.order == ["A", "B", "C"]
    assert analysis.loops == []
    assert analysis.loop_connections == []
    assert sorted(analysis.graph.edges) == [("A", "B"), ("B", "C")]
    assert analysis.schedule() == (["A", "B", "C"], [1, 1, 1], [False, False, False])


def test_feedthrough_nobody_reads_is_no_dependency() -> None:
    # C computes y from u without delay, but nobody reads y, so C waits for no one: it shares
    # A's generation and, with no connection between them, keeps the order of addition.
    components = {"C": FEEDTHROUGH, "B": FEEDTHROUGH, "A": NO_FEEDTHROUGH}
    connections = [("A", "y", "B", "u"), ("B", "y", "C", "u")]
    analysis = analyze(components, connections)
    assert sorted(analysis.graph.edges) == [("A", "B")]
    assert analysis.generations == [["C", "A"], ["B"]]


def test_inside_a_generation_consumers_run_before_their_delayed_producers() -> None:
    # No feedthrough anywhere: one generation, and each consumer steps before its producer so
    # that it reads the value of the start of the macro step (SysSimX's Gauss-Seidel).
    components = {"A": NO_FEEDTHROUGH, "B": NO_FEEDTHROUGH, "C": NO_FEEDTHROUGH}
    analysis = analyze(components, [("A", "y", "B", "u"), ("B", "y", "C", "u")])
    assert analysis.generations == [["C", "B", "A"]]
    # A delayed cycle cannot be ordered so: the connection given first decides.
    cycle = analyze({"A": NO_FEEDTHROUGH, "B": NO_FEEDTHROUGH},
                    [("B", "y", "A", "u"), ("A", "y", "B", "u")])
    assert cycle.generations == [["A", "B"]]


def test_two_component_loop_is_one_group() -> None:
    components = {"Source": NO_FEEDTHROUGH, "Gain": FEEDTHROUGH, "Sum": {"y": {"u", "w"}}}
    connections = [
        ("Source", "y", "Sum", "w"),
        ("Sum", "y", "Gain", "u"),
        ("Gain", "y", "Sum", "u"),
    ]
    analysis = analyze(components, connections)
    assert analysis.loops == [["Gain", "Sum"]]
    assert analysis.generations == [["Source"], ["Gain", "Sum"]]
    assert analysis.loop_connections == [("Sum", "y", "Gain", "u"), ("Gain", "y", "Sum", "u")]
    assert analysis.schedule() == (["Source", "Gain", "Sum"], [1, 2], [False, True])


def test_self_loop_is_a_loop_of_one() -> None:
    components = {"Solo": FEEDTHROUGH}
    connections = [("Solo", "y", "Solo", "u")]
    analysis = analyze(components, connections)
    assert analysis.loops == [["Solo"]]
    assert analysis.loop_connections == connections
    assert analysis.schedule() == (["Solo"], [1], [True])


def test_loop_broken_by_an_output_without_feedthrough() -> None:
    # Controller reads the plant without delay; the plant integrates the control: no loop,
    # and the plant (the delayed producer) runs first so the controller sees its new output.
    components = {"Controller": FEEDTHROUGH, "Plant": NO_FEEDTHROUGH}
    connections = [("Controller", "y", "Plant", "u"), ("Plant", "y", "Controller", "u")]
    analysis = analyze(components, connections)
    assert analysis.loops == []
    assert analysis.generations == [["Plant"], ["Controller"]]
    assert list(analysis.graph.edges) == [("Plant", "Controller")]


def test_feedthrough_to_an_unconnected_output_makes_no_loop() -> None:
    # B reads u without delay only for y, which nobody reads; its state output z closes the
    # cycle with a delay.
    components = {"A": FEEDTHROUGH, "B": {"y": {"u"}, "z": set()}}
    connections = [("A", "y", "B", "u"), ("B", "z", "A", "u")]
    analysis = analyze(components, connections)
    assert analysis.loops == []
    assert analysis.generations == [["B"], ["A"]]


def test_declared_feedthrough_is_taken_as_given() -> None:
    # The same wiring is a loop or not depending only on what the components declare.
    connections = [("P", "y", "Q", "u"), ("Q", "y", "P", "u")]
    declared = analyze({"P": {"y": {"u"}}, "Q": {"y": {"u"}}}, connections)
    undeclared = analyze({"P": {"y": set()}, "Q": {"y": {"u"}}}, connections)
    assert declared.loops == [["P", "Q"]]
    assert undeclared.loops == []
    assert undeclared.generations == [["P"], ["Q"]]


def test_generations_of_two_pendulums_and_a_spring() -> None:
    pendulum = {"theta": set(), "omega": set()}
    spring = {"tau1": {"theta1", "theta2"}, "tau2": {"theta1", "theta2"}}
    components = {"Spring": spring, "P1": pendulum, "P2": pendulum}
    connections = [
        ("P1", "theta", "Spring", "theta1"),
        ("P2", "theta", "Spring", "theta2"),
        ("Spring", "tau1", "P1", "torque"),
        ("Spring", "tau2", "P2", "torque"),
    ]
    analysis = analyze(components, connections)
    assert analysis.generations == [["P1", "P2"], ["Spring"]]
    assert analysis.loops == []


def test_loops_sharing_a_component_are_one_group_and_generations_follow() -> None:
    components = {
        "Feed": NO_FEEDTHROUGH,
        "A": {"y": {"u", "v"}},
        "B": FEEDTHROUGH,
        "C": FEEDTHROUGH,
        "Sink": FEEDTHROUGH,
    }
    connections = [
        ("Feed", "y", "C", "u"),
        ("A", "y", "B", "u"),
        ("B", "y", "A", "u"),
        ("A", "y", "Sink", "u"),
        ("Sink", "y", "A", "v"),
    ]
    analysis = analyze(components, connections)
    assert analysis.loops == [["A", "B", "Sink"]]
    # C's output is unconnected, so Feed -> C is delayed: one generation, C before Feed.
    assert analysis.generations == [["A", "B", "Sink", "C", "Feed"]]
    assert analysis.schedule() == (["A", "B", "Sink", "C", "Feed"], [3, 1, 1], [True, False, False])


def test_unknown_component_in_a_connection_is_named() -> None:
    with pytest.raises(ValueError, match=r"unknown component 'Ghost'.*components: A"):
        analyze({"A": FEEDTHROUGH}, [("Ghost", "y", "A", "u")])


MODEL_DESCRIPTION = """<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="Mixer" guid="{mixer}"
    numberOfEventIndicators="0">
  <CoSimulation modelIdentifier="Mixer"/>
  <ModelVariables>
    <ScalarVariable name="a" valueReference="0" causality="input" variability="continuous">
      <Real start="0"/></ScalarVariable>
    <ScalarVariable name="b" valueReference="1" causality="input" variability="continuous">
      <Real start="0"/></ScalarVariable>
    <ScalarVariable name="x" valueReference="2" causality="local" variability="continuous"
        initial="exact"><Real start="0"/></ScalarVariable>
    <ScalarVariable name="der(x)" valueReference="3" causality="local"
        variability="continuous"><Real derivative="3"/></ScalarVariable>
    <ScalarVariable name="sum" valueReference="4" causality="output" variability="continuous">
      <Real/></ScalarVariable>
    <ScalarVariable name="state" valueReference="5" causality="output"
        variability="continuous"><Real/></ScalarVariable>
    <ScalarVariable name="only_b" valueReference="6" causality="output"
        variability="continuous"><Real/></ScalarVariable>
    <ScalarVariable name="anything" valueReference="7" causality="output"
        variability="continuous"><Real/></ScalarVariable>
  </ModelVariables>
  <ModelStructure>
    <Outputs>
      <Unknown index="5" dependencies="1 2"/>
      <Unknown index="6" dependencies="3"/>
      <Unknown index="7" dependencies="2 3"/>
      <Unknown index="8"/>
    </Outputs>
    <Derivatives>
      <Unknown index="4" dependencies="1"/>
    </Derivatives>
    <InitialUnknowns>
      <Unknown index="4"/>
      <Unknown index="5"/>
      <Unknown index="6"/>
      <Unknown index="7"/>
      <Unknown index="8"/>
    </InitialUnknowns>
  </ModelStructure>
</fmiModelDescription>
"""


def test_feedthrough_from_model_structure(tmp_path: Path) -> None:
    xml = tmp_path / "modelDescription.xml"
    xml.write_text(MODEL_DESCRIPTION)
    model_description = read_model_description(str(xml), validate=False)
    assert feedthrough_from_model_description(model_description) == {
        "sum": {"a", "b"},
        "state": set(),  # depends on a state only
        "only_b": {"b"},  # the state among its dependencies is not an input
        "anything": {"a", "b"},  # no dependencies attribute: depends on all inputs
    }


# OMSimulator's DualMassOscillator shape: mass 1 (x1, v1 states; a1 = F / m1 - ...) feeds the
# coupling spring, whose force F depends on x1 and v1; a1 goes to the spring, which reads it
# for nothing. The components drive each other, the variables do not.
DUAL_MASS = {"mass1": {"x1": set(), "v1": set(), "a1": {"F"}},
             "spring": {"F": {"x1", "v1"}}}
DUAL_MASS_CONNECTIONS = [("mass1", "x1", "spring", "x1"), ("mass1", "v1", "spring", "v1"),
                         ("mass1", "a1", "spring", "a1"), ("spring", "F", "mass1", "F")]


def test_component_cycle_without_a_variable_cycle_is_no_loop() -> None:
    # Added spring first: the order comes from the variables (x1 and v1 depend on nothing),
    # not from the order of addition.
    components = {"spring": DUAL_MASS["spring"], "mass1": DUAL_MASS["mass1"]}
    analysis = analyze(components, DUAL_MASS_CONNECTIONS)
    assert analysis.loops == []
    assert analysis.order == ["mass1", "spring"]
    assert analysis.schedule() == (["mass1", "spring"], [1, 1], [False, False])
    # a1 needs F, which needs x1: the connection that closes the component cycle is delayed
    assert analysis.delayed_connections == [("spring", "F", "mass1", "F")]
    assert sorted(analysis.graph.edges) == [("mass1", "spring")]


def test_a_loop_through_variables_is_found_beside_a_component_cycle() -> None:
    # the same shape where F also depends on a1: now a variable cycle F -> a1 -> F
    components = {"mass1": DUAL_MASS["mass1"], "spring": {"F": {"x1", "v1", "a1"}}}
    analysis = analyze(components, DUAL_MASS_CONNECTIONS)
    assert analysis.loops == [["mass1", "spring"]]
    assert analysis.delayed_connections == []


# libcosim's quarter truck shape: two FMUs that declare no output dependencies, one power bond
TRUCK = {"chassis": {"velocity": {"force"}}, "wheel": {"out_spring_damper_f": {"in_vel"}}}
TRUCK_CONNECTIONS = [("chassis", "velocity", "wheel", "in_vel"),
                     ("wheel", "out_spring_damper_f", "chassis", "force")]
TRUCK_UNDECLARED = {"chassis": {"velocity"}, "wheel": {"out_spring_damper_f"}}


def test_a_loop_made_by_undeclared_dependencies_is_solved_or_coupled_as_chosen() -> None:
    solved = analyze(TRUCK, TRUCK_CONNECTIONS, TRUCK_UNDECLARED, "all")
    assert solved.loops == [["chassis", "wheel"]]
    assert solved.undeclared_in_loops == ["chassis", "wheel"]
    coupled = analyze(TRUCK, TRUCK_CONNECTIONS, TRUCK_UNDECLARED, "none")
    assert coupled.loops == []
    assert coupled.undeclared_in_loops == ["chassis", "wheel"]
    assert coupled.undeclared_dependencies == "none"
    # a declared dependency stays, whatever is chosen for undeclared ones
    declared = analyze(TRUCK, TRUCK_CONNECTIONS, {"wheel": {"out_spring_damper_f"}}, "none")
    assert declared.loops == []
    assert declared.undeclared_in_loops == ["wheel"]
    real_loop = analyze(TRUCK, TRUCK_CONNECTIONS, {}, "none")
    assert real_loop.loops == [["chassis", "wheel"]]
    assert real_loop.undeclared_in_loops == []
    with pytest.raises(ValueError, match="undeclared_dependencies"):
        analyze(TRUCK, TRUCK_CONNECTIONS, TRUCK_UNDECLARED, "some")
