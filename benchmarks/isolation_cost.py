"""What isolation costs: the same System run with its FMU in process and isolated (the binary in
a host process, every fmi2 call over a socket), side by side in one run.

  grid       one FMU, no events, 10 000 steps of dt 1e-3 (pendulum_euler: 10 Euler substeps
             per doStep; pendulum_cvode at its default tolerance)
  seed       the seed scenario (examples/pendulum_wall.py, CVODE FMU): 3 s, dt 0.05, three wall
             hits located by rollback, so fmi2Get/SetFMUstate cross the socket too

For each case: the wall time per macro step in process and isolated (median of --repeat runs,
the two alternating; five times as many for the short seed run), their ratio, the time
isolation adds per doStep, and whether the results are bit-identical. A doStep and the
fmi2GetReal of the outputs after it share one round trip to the host. For scale, the same run
also times a bare round trip over a socket between two processes (a Python echo child, so it
includes some interpreter time on both ends).

    python benchmarks/isolation_cost.py [--repeat N]
"""

from __future__ import annotations

import argparse
import functools
import gc
import socket
import statistics
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from syssimx import FMUComponent, System, fmus

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
GRID_STEPS, GRID_DT = 10_000, 1e-3
ROUND_TRIPS = 20_000
ECHO = ("import socket\n"
        "s = socket.socket(fileno={fd})\n"
        "while (b := s.recv(64)):\n"
        "    s.sendall(b)\n")

Run = tuple[float, int, int, int, np.ndarray]  # wall, macro steps, doSteps, fmi2 calls, theta


def grid_run(fmu: str, isolated: bool) -> Run:
    pendulum = FMUComponent("P", fmus.path(fmu), isolated=isolated)
    pendulum.set_parameters(theta0=0.5, omega0=0.0)
    system = System("grid")
    system.add_component(pendulum)
    system.initialize(0.0)
    before = pendulum.instance.counters()
    start = time.perf_counter()
    result = system.run(0.0, GRID_STEPS * GRID_DT, GRID_DT)
    wall = time.perf_counter() - start
    return measured(wall, result.statistics.macro_steps, before, pendulum,
                    result["P"][1]["theta"])


def seed_run(isolated: bool) -> Run:
    sys.path.insert(0, str(EXAMPLES))
    import pendulum_wall

    pendulum_wall.FMUComponent = functools.partial(FMUComponent, isolated=isolated)
    system, pendulum = pendulum_wall.build("cvode")
    before = pendulum.instance.counters()
    start = time.perf_counter()
    result = system.run(0.0, 3.0, 0.05)
    wall = time.perf_counter() - start
    return measured(wall, result.statistics.macro_steps, before, pendulum,
                    np.array([event.t for event in result.events]))


def measured(wall: float, macro_steps: int, before: dict[str, int], pendulum: FMUComponent,
             values: np.ndarray) -> Run:
    after = pendulum.instance.counters()
    calls = sum(after[k] - before[k] for k in ("do_step", "get_state", "set_state",
                                               "get_values", "set_values"))
    outcome = (wall, macro_steps, after["do_step"] - before["do_step"], calls, values.copy())
    pendulum.free()
    return outcome


def compare(name: str, run: Callable[[bool], Run], repeat: int) -> None:
    walls: dict[bool, list[float]] = {False: [], True: []}
    last: dict[bool, Run] = {}
    for _ in range(repeat):
        for isolated in (False, True):
            gc.collect()
            last[isolated] = run(isolated)
            walls[isolated].append(last[isolated][0])
    here, there = statistics.median(walls[False]), statistics.median(walls[True])
    _, steps, do_steps, calls, values = last[True]
    identical = np.array_equal(last[False][4], values) and last[False][1:4] == last[True][1:4]
    print(f"{name}: {steps} macro steps, {do_steps} doStep, {calls} fmi2 calls per run")
    print(f"  in process {here / steps * 1e6:8.2f} us per step   isolated "
          f"{there / steps * 1e6:8.2f} us per step   ratio {there / here:5.1f}")
    print(f"  isolation adds {(there - here) / do_steps * 1e6:.2f} us per doStep; "
          f"results bit-identical: {'yes' if identical else 'NO'}")


def socket_round_trip() -> float:
    """Seconds per 64-byte round trip to an echoing child process."""
    ours, theirs = socket.socketpair()
    with subprocess.Popen([sys.executable, "-c", ECHO.format(fd=theirs.fileno())],
                          pass_fds=(theirs.fileno(),),
                          stdin=subprocess.DEVNULL) as child:
        theirs.close()
        message = bytes(64)
        ours.sendall(message)
        ours.recv(64)  # the child is up
        start = time.perf_counter()
        for _ in range(ROUND_TRIPS):
            ours.sendall(message)
            ours.recv(64)
        elapsed = time.perf_counter() - start
        ours.close()
        child.wait()
    return elapsed / ROUND_TRIPS


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    compare("grid, pendulum_euler, dt 1e-3", functools.partial(grid_run, "pendulum_euler"),
            args.repeat)
    compare("grid, pendulum_cvode, dt 1e-3", functools.partial(grid_run, "pendulum_cvode"),
            args.repeat)
    compare("seed scenario, pendulum_cvode, 3 s, 3 events", seed_run, 5 * args.repeat)
    print(f"bare socket round trip between two processes: {socket_round_trip() * 1e6:.2f} us")


if __name__ == "__main__":
    main()
