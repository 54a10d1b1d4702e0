"""What a Python component costs per step: the SysSimX quickstart (LinearSource -> Integrator,
two Python `CoSimComponent`s, examples/quickstart.py) run by `System.run`, against the same
run with a pendulum FMU in place of each Python component and against the engine's own time
for an empty step (a `gain` FMU), all in one process.

Printed: microseconds of CPU per step of the whole run and per Python component step (the
run's CPU time less the FMU run's, over the Python components; CPU time, not wall time: on a
shared machine the wall counts the other processes' turns too). The comparison with SysSimX
0.4.3 on the same quickstart is benchmarks/yaml_system.py (SysSimX in its own virtual
environment).

    python benchmarks/python_component.py [--steps 20000] [--repeats 5]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
from quickstart import Integrator, LinearSource
from syssimx import Connection, FMUComponent, System, fmus

DT = 0.01


def quickstart() -> System:
    system = System("quickstart")
    system.add_component(LinearSource("LinearSource", a=1.0, b=0.0))
    system.add_component(Integrator("Integrator", x0=0.0))
    system.add_connection(Connection("LinearSource", "y", "Integrator", "u"))
    return system


def gains() -> System:
    system = System("gains")
    system.add_component(FMUComponent("A", fmus.path("gain")))
    system.add_component(FMUComponent("B", fmus.path("gain")))
    system.add_connection(Connection("A", "y", "B", "u"))
    return system


def per_step(system: System, steps: int, repeats: int) -> tuple[float, float]:
    """Median CPU microseconds per step over `repeats` runs of `steps` steps; the last value
    of the last component's first output."""
    walls = []
    for _ in range(repeats):
        system.initialize(0.0)
        start = time.process_time()
        result = system.run(0.0, steps * DT, DT)
        walls.append(time.process_time() - start)
    last = list(system.components)[-1]
    values = next(iter(result[last][1].values()))
    return statistics.median(walls) / steps * 1e6, float(values[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=int, default=20000)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    python_step, value = per_step(quickstart(), args.steps, args.repeats)
    fmu_step, _ = per_step(gains(), args.steps, args.repeats)
    exact = sum(k * DT for k in range(args.steps)) * DT  # forward Euler of y' = t
    print(f"{args.steps} steps of {DT}, median of {args.repeats}")
    print(f"{'case':<44} {'us/step':>8}")
    print(f"{'quickstart: two Python components':<44} {python_step:8.2f}")
    print(f"{'two gain FMUs (the engine without Python)':<44} {fmu_step:8.2f}")
    print(f"{'per Python component step':<44} {(python_step - fmu_step) / 2:8.2f}")
    print(f"Integrator.y at the end: {value:.10g} (forward Euler: {exact:.10g})")


if __name__ == "__main__":
    main()
