"""The members of benchmarks/run_cost.py run by Ecos (ecospy), in ecospy's own virtual
environment: a child process of run_cost.py, one round of members per line it reads.

Each line is a JSON list of theta0 values; for each member the simulation is reset, theta0 set,
initialized at 0 and stepped 20 times at dt 0.05 (the way ecospy's Python API runs a member:
reset, set_real, init, step). Mode "final" steps 20 at once and reads theta at the end; mode
"recorded" steps one at a time and reads theta and omega after each step (the samples the
other paths keep). The answer per line: [CPU seconds of the round, each member's theta(1 s)].
It imports nothing but ecospy and the standard library (ecospy's environment has no numpy).

    python ecos_members.py FMU_PATH final|recorded
"""

from __future__ import annotations

import json
import sys
import time

from ecospy import EcosSimulation, EcosSimulationStructure

DT, STEPS = 0.05, 20


def main() -> None:
    path, mode = sys.argv[1], sys.argv[2]
    structure = EcosSimulationStructure()
    structure.add_model("P", path)
    simulation = EcosSimulation(structure=structure, step_size=DT)
    for line in sys.stdin:
        thetas = json.loads(line)
        start = time.process_time()
        finals, kept = [], []
        for theta in thetas:
            simulation.reset()
            simulation.set_real("P::theta0", theta)
            simulation.init(0.0)
            if mode == "recorded":
                rows = [(simulation.get_real("P::theta"), simulation.get_real("P::omega"))]
                for _ in range(STEPS):
                    simulation.step(1)
                    rows.append((simulation.get_real("P::theta"), simulation.get_real("P::omega")))
                kept.append(rows)
                finals.append(rows[-1][0])
            else:
                simulation.step(STEPS)
                finals.append(simulation.get_real("P::theta"))
        cpu = time.process_time() - start
        print(json.dumps([cpu, finals]), flush=True)


if __name__ == "__main__":
    main()
