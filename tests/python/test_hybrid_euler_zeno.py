"""The bouncing ball whose FMU integrates with explicit Euler (1e-4 s steps) and whose bounce
the master applies (restitution 0.8).

Explicit Euler gains speed at every bounce: a flight that starts at speed u lands at
u + g h (h the Euler step), so the rebound speeds settle at e g h / (1 - e) = 3.9 mm/s instead
of shrinking to zero, and the flights at h (1 + e) / (1 - e) = 0.9 ms: the ball would bounce
0.8 micrometres high for ever (6 708 events in 10 s). Crossings that come back within a tenth of
the communication step and stop shrinking are chattering, so the run ends with a ZenoError just
past the accumulation point of the exact ball, like the CVODE ball.
"""

from __future__ import annotations

import bouncing_ball
import numpy as np
import pytest
from syssimx import System, ZenoError

E, G, H0 = 0.8, 9.81, 1.0
T_INF = np.sqrt(2 * H0 / G) * (1 + E) / (1 - E)  # the exact ball's accumulation point


def euler_ball(direction: int) -> System:
    system = bouncing_ball.build("bouncing_ball_continuous_euler", direction)
    system.initialize(0.0)
    return system


@pytest.mark.parametrize("direction", [-1, 0])
def test_euler_ball_ends_in_a_zeno_error_at_the_accumulation_point(direction: int):
    system = euler_ball(direction)
    with pytest.raises(ZenoError, match=r"within a tenth of the communication step, and its "
                                        r"intervals no longer shrink") as info:
        system.run(0.0, 10.0, 0.01)
    assert info.value.component == "Ball" and info.value.event == "floor"
    # Euler's first impact is 5e-5 s late, and its flights stop shrinking at 0.9 ms
    assert T_INF < info.value.time < T_INF + 0.05
    events = system.history.get_event_history("Ball", "floor")
    assert len(events) < 50
    intervals = np.diff([e.t for e in events])
    assert intervals[-1] > 0.8e-3  # a limit cycle, not an accumulation
    t, data = system.get_history()["Ball"]
    assert t[-1] == pytest.approx(info.value.time, abs=1e-12)
    assert data["h"].min() > -1e-8  # never through the floor
