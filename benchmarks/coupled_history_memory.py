"""History memory of a long run, measured in a fresh process (coupled_overhead.py runs it).

N pendulum_euler FMUs x 3 outputs x STEPS macro steps of DT through the Python System. Prints
one JSON line: the bytes the engine holds for the history (System.history_bytes, i.e.
ssx_history_bytes), the raw float64 size of the same samples (3 outputs per FMU plus one time
axis, STEPS + 1 samples), and the process's peak RSS during system.run (getrusage) minus its
resident size when the run starts (/proc/self/statm). The resident size, not the peak, is the
base because loading 100 FMUs leaves a higher transient peak behind; a fresh process keeps
earlier benchmarks' allocations out of both.

    python coupled_history_memory.py N STEPS DT
"""

from __future__ import annotations

import json
import resource
import sys
from pathlib import Path

from syssimx import FMUComponent, System, fmus

OUTPUTS_PER_FMU = 3
FLOAT64_BYTES = 8


def peak_rss_bytes() -> int:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024  # Linux: KiB


def current_rss_bytes() -> int:
    resident_pages = int(Path("/proc/self/statm").read_text().split()[1])
    return resident_pages * resource.getpagesize()


def main() -> None:
    count, steps, dt = int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3])
    system = System("history memory")
    for i in range(count):
        pendulum = FMUComponent(f"P{i}", fmus.path("pendulum_euler"))
        pendulum.set_parameters(theta0=0.5, omega0=0.0)
        system.add_component(pendulum)
    system.initialize(0.0)
    before = current_rss_bytes()
    result = system.run(0.0, steps * dt, dt)
    growth = peak_rss_bytes() - before
    samples = len(result.micro)
    raw = samples * (OUTPUTS_PER_FMU * count + 1) * FLOAT64_BYTES
    print(json.dumps({"engine_bytes": system.history_bytes(), "raw_bytes": raw,
                      "rss_growth_bytes": growth, "samples": samples}))


if __name__ == "__main__":
    main()
