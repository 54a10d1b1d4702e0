"""FMU state round trips through fmpy: get, run on, set back, run again; and serialization into
a fresh instance."""

from __future__ import annotations

import pytest

T1, T2, DT = 0.2, 0.7, 0.01


def run(fmu, t_from: float, t_to: float) -> tuple[float, float]:
    for k in range(round((t_to - t_from) / DT)):
        fmu.slave.doStep(t_from + k * DT, DT)
    return fmu.get("theta"), fmu.get("omega")


@pytest.mark.parametrize(
    ("name", "relative"),
    [
        ("pendulum_euler", 0.0),  # the same arithmetic again: bit-identical
        ("pendulum_cvode", 1e-9),  # CVODE restarts at t1, agreeing to its tolerance 1e-10
        ("pendulum_contact_euler", 0.0),
        # the restarted run also locates the impact at 0.465 s anew, to CVODE's tolerance
        ("pendulum_contact_cvode", 5e-9),
    ],
)
def test_set_state_replays_the_run(open_fmu, name: str, relative: float) -> None:
    starts = {"theta0": 0.5}
    tolerance = 1e-10 if name.endswith("cvode") else None
    fmu = open_fmu(name, starts=starts, tolerance=tolerance)
    run(fmu, 0.0, T1)
    state = fmu.slave.getFMUState()
    first = run(fmu, T1, T2)
    fmu.slave.setFMUState(state)
    second = run(fmu, T1, T2)
    for a, b in zip(first, second, strict=True):
        assert a == pytest.approx(b, rel=relative, abs=0.0)

    serialized = fmu.slave.serializeFMUState(state)
    fresh = open_fmu(name, starts=starts, tolerance=tolerance)
    copy = fresh.slave.deserializeFMUState(serialized)
    fresh.slave.setFMUState(copy)
    assert run(fresh, T1, T2) == second
    fresh.slave.freeFMUState(copy)
    fmu.slave.freeFMUState(state)


def test_reset_gives_the_same_run(open_fmu) -> None:
    fmu = open_fmu("pendulum_cvode", starts={"theta0": 0.5}, tolerance=1e-10)
    before = run(fmu, 0.0, T1)
    fmu.slave.reset()
    fmu.slave.setupExperiment(tolerance=1e-10, startTime=0.0)
    fmu.slave.enterInitializationMode()
    fmu.set("theta0", 0.5)
    fmu.slave.exitInitializationMode()
    assert run(fmu, 0.0, T1) == before
