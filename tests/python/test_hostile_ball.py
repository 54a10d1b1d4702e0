"""FMUSDK's bouncing ball as Model Exchange, quirks included (tests/fmus/HostileBall).

- Its bounce leaves the indicator h a hair below zero (h := -residue), so the rise crosses it
  again, upwards, about 1e-14 s later. That crossing is the bounce's residue, not a second
  bounce: before, it ended the run with a ZenoError 1.79e-14 s after the first bounce. The
  bounces are those of the closed form, t1 = sqrt(2 h0 / g), then flights of 2 e^k v1 / g,
  and FMPy's (FMPY_BOUNCES).
- A derivative that turns NaN is an error naming the component, the derivative and the time.
"""

from __future__ import annotations

import math
import re

import pytest
from fixture_fmus import fmu_path
from syssimx import FMUComponent, System
from syssimx.errors import SimulationError

G, E, H0 = 9.81, 0.7, 1.0
# FMPy 0.3.32 on hostile_ball.fmu (FMI 2.0 Model Exchange, solver CVode, relative_tolerance
# 1e-10, stop_time 2, output_interval 0.01, record_events): its event instants, each bounce
# followed by its residue 1.8e-14 to 4.3e-14 s later (FMPy handles the residue as an event)
FMPY_BOUNCES = [0.45152364095156383, 1.083656738256656, 1.5261499063121422,
                1.8358951238671315]


def closed_form_bounces(count: int) -> list[float]:
    t1 = math.sqrt(2 * H0 / G)
    times = [t1]
    for k in range(1, count):
        times.append(times[-1] + 2 * E**k * t1)  # v1 = g t1: a flight of 2 e^k v1 / g
    return times


def ball(name: str, tolerance: float = 1e-10, **parameters: float) -> System:
    component = FMUComponent("B", fmu_path(name), tolerance=tolerance,
                             interface="model-exchange")
    component.set_parameters(**parameters)
    system = System("ball")
    system.add_component(component)
    system.initialize(0.0)
    return system


@pytest.mark.parametrize("name", ["hostile_ball", "hostile_ball_fmi1_me"])
def test_the_bounce_residue_is_no_event_and_the_bounces_follow_the_closed_form(name: str):
    result = ball(name).run(0.0, 2.0, 0.01)
    bounces = [event.t for event in result.events]
    # four bounces before t = 2 s, each once: the residues 1.8e-14 s after them are not events
    assert len(bounces) == 4
    for reference in (closed_form_bounces(4), FMPY_BOUNCES):
        assert max(abs(t - exact) for t, exact in zip(bounces, reference, strict=True)) < 1e-8
    _, values = result["B"]
    assert values["h"].min() > -1e-9  # the ball never sinks through the floor


def test_a_nan_derivative_stops_the_run_naming_the_component_and_the_time():
    """Before: CVODE took the NaN into its states, where this FMU refused them a step later
    (t=0.3, naming fmiSetContinuousStates); an FMU that takes NaN states kept CVODE going
    without end."""
    system = ball("hostile_ball_fmi1_me", nan_time=0.25)
    with pytest.raises(SimulationError) as caught:
        system.run(0.0, 1.0, 0.1)
    named = re.match(r"component 'B': derivative 1 \(of 2\) is nan at t=(\S+): the integrator "
                     "cannot go on from a non-finite derivative", str(caught.value))
    assert named is not None, str(caught.value)
    # the first time CVODE asked for the derivatives on or after 0.25, within the step to 0.3
    assert 0.25 <= float(named.group(1)) == caught.value.time <= 0.3
    t, _ = system.get_history()["B"]
    assert t[-1] == pytest.approx(0.2)  # the samples before the failure are kept

