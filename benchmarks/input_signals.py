"""An input signal fed to an FMU: the engine's TableSource against a Python source and FMPy.

pendulum_euler (internal Euler step 1e-4) over 10 s in communication steps of 1e-3 (10 000
steps), its torque from a table of 1 001 rows (a sine sampled every 10 ms, with a jump at 5 s),
Jacobi coupling (FMPy's input timing). Measured side by side in one run, median of --repeat:

  no input      the pendulum alone: the floor
  TableSource   the table evaluated by the engine, no Python per step
  Python source a CoSimComponent doing numpy's interp per step (called back from C)
  FMPy          fmpy.simulate_fmu(input=...) on the same FMU and grid

The TableSource and FMPy results are checked equal before anything is printed.

    python benchmarks/input_signals.py [--repeat N]
"""

from __future__ import annotations

import argparse
import gc
import statistics
import time
from collections.abc import Callable

import numpy as np
from fmpy import simulate_fmu
from syssimx import (
    Connection,
    CoSimComponent,
    FMUComponent,
    JacobiAlgorithm,
    PortSpec,
    PortType,
    System,
    TableSource,
    fmus,
)

DT, STOP = 1e-3, 10.0
STEPS = round(STOP / DT)


def torque_table() -> np.ndarray:
    t = np.linspace(0.0, STOP, 1001)
    torque = 20.0 * np.sin(2.0 * np.pi * 0.5 * t)
    jump = int(np.searchsorted(t, 5.0))
    t = np.insert(t, jump, 5.0)  # a repeated stamp: the torque jumps by 10 N.m at 5 s
    torque = np.insert(torque, jump, torque[jump] + 10.0)
    table = np.empty(len(t), dtype=[("time", np.float64), ("torque", np.float64)])
    table["time"], table["torque"] = t, torque
    return table


class InterpolatingSource(CoSimComponent):
    """The torque from numpy's interp, in Python at every step."""

    def __init__(self, name: str, table: np.ndarray) -> None:
        super().__init__(name)
        self.table = table
        self.value = float(table["torque"][0])
        self.output_specs["torque"] = PortSpec("torque", PortType.REAL, "out")
        self._sync_ports()

    def _do_step_internal(self, t: float, dt: float) -> None:
        self.value = float(np.interp(t + dt, self.table["time"], self.table["torque"]))

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        self.outputs["torque"].set(self.value, t)


def pendulum_system(source: CoSimComponent | None) -> System:
    system = System("driven pendulum")
    system.add_component(FMUComponent("P", fmus.path("pendulum_euler")))
    if source is not None:
        system.add_component(source)
        system.add_connection(Connection(source.name, "torque", "P", "torque"))
    system.set_algorithm(JacobiAlgorithm())
    return system


def timed_run(make: Callable[[], CoSimComponent | None]) -> tuple[float, np.ndarray]:
    gc.collect()  # earlier systems sit in reference cycles: free them outside the timing
    system = pendulum_system(make())
    system.initialize(0.0)
    start = time.perf_counter()
    theta = system.run(0.0, STOP, DT)["P"][1]["theta"]
    return time.perf_counter() - start, np.array(theta)


def timed_fmpy(table: np.ndarray) -> tuple[float, np.ndarray]:
    start = time.perf_counter()
    result = simulate_fmu(fmus.path("pendulum_euler"), stop_time=STOP, output_interval=DT,
                          input=table, output=["theta"])
    return time.perf_counter() - start, np.array(result["theta"])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    repeat = parser.parse_args().repeat
    table = torque_table()
    variants: dict[str, Callable[[], tuple[float, np.ndarray]]] = {
        "no input": lambda: timed_run(lambda: None),
        "TableSource": lambda: timed_run(lambda: TableSource("u", table)),
        "Python source": lambda: timed_run(lambda: InterpolatingSource("u", table)),
        "FMPy simulate_fmu": lambda: timed_fmpy(table),
    }
    walls: dict[str, list[float]] = {name: [] for name in variants}
    results: dict[str, np.ndarray] = {}
    for _ in range(repeat):  # interleaved, so drifting machine load hits every variant alike
        for name, run in variants.items():
            wall, theta = run()
            walls[name].append(wall)
            results[name] = theta
    difference = np.max(np.abs(results["TableSource"] - results["FMPy simulate_fmu"]))
    assert difference < 1e-12, f"TableSource and FMPy differ by {difference}"
    median = {name: statistics.median(values) for name, values in walls.items()}
    table_cost = (median["TableSource"] - median["no input"]) / STEPS
    print(f"pendulum_euler, {STEPS} steps of {DT} s, torque table of {len(table)} rows, "
          f"median of {repeat} (TableSource = FMPy to {difference:.1e} rad)")
    for name, wall in median.items():
        print(f"  {name:<18} {wall * 1e3:9.2f} ms  {wall / median['TableSource']:7.2f}x "
              f"TableSource")
    print(f"  the table and the torque written to the FMU add {table_cost * 1e9:.0f} ns per step")


if __name__ == "__main__":
    main()
