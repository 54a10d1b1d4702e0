"""The SysSimX side of coupled_overhead.py: run inside the SysSimX-from-PyPI environment.

N uncoupled pendulum_euler FMUs, Gauss-Seidel (SysSimX's default), STEPS macro steps of DT.
Prints one JSON line: best wall time of system.run over REPEAT runs and the final theta of the
first and last pendulum (to check that both packages simulated the same thing).

    python coupled_syssimx_child.py FMU_PATH N STEPS DT REPEAT
"""

from __future__ import annotations

import json
import sys
import time

from syssimx import FMUComponent, System


def build(fmu_path: str, count: int) -> System:
    system = System(name="pendulums")
    for i in range(count):
        pendulum = FMUComponent(f"P{i}", fmu_path)
        pendulum.set_parameters(theta0=0.5, omega0=0.0)
        system.add_component(pendulum)
    system.initialize(t0=0.0)
    return system


def main() -> None:
    fmu_path, count, steps = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    dt, repeat = float(sys.argv[4]), int(sys.argv[5])
    walls = []
    for _ in range(repeat):
        system = build(fmu_path, count)
        start = time.perf_counter()
        system.run(0.0, steps * dt, dt)
        walls.append(time.perf_counter() - start)
    final = [system.components[f"P{i}"].get_outputs()["theta"].magnitude
             for i in (0, count - 1)]
    print(json.dumps({"wall": min(walls), "final_theta": final}))


if __name__ == "__main__":
    main()
