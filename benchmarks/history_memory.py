"""History memory and cost when runs are continued, results are kept, or a step size is a typo.

Pendulum_euler FMUs (theta0 0.5), Gauss-Seidel, no events. Every figure is measured side by
side in this one process; the resident size (RSS, /proc/self/statm) is read before and after
each case, after a garbage collection.

  one run      N_FMUS FMUs, STEPS steps of DT in one System.run: the reference wall time and
               memory (the grid is reserved ahead, nothing moves)
  chunks       the same STEPS as CHUNKS continued runs, `result = system.run(...)` each time,
               so the previous result still holds its arrays while the next run records: the
               engine copies a held history only when it outgrows it, into twice the room
  all kept     the same chunks, every result kept in a list: each result's arrays keep the
               history as it was, shared by later results until the engine outgrows it
  typo         one FMU, dt 1e-9 over 1 s (10^9 steps, 36 GB if reserved at once), stopped by
               timeout=TYPO_SECONDS: the history holds what was recorded

    python benchmarks/history_memory.py
"""

from __future__ import annotations

import gc
import os
import time
from pathlib import Path

from syssimx import FMUComponent, SimulationTimeoutError, System, fmus

N_FMUS, STEPS, DT, CHUNKS = 10, 100_000, 1e-3, 200
TYPO_DT, TYPO_SECONDS = 1e-9, 1.0
SAMPLE_BYTES = 8 + 4 + 3 * 8  # time, micro index, three outputs per FMU


def resident_bytes() -> int:
    return int(Path("/proc/self/statm").read_text().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def pendulums(count: int) -> System:
    system = System(f"{count} pendulums")
    for i in range(count):
        pendulum = FMUComponent(f"P{i}", fmus.path("pendulum_euler"))
        pendulum.set_parameters(theta0=0.5, omega0=0.0)
        system.add_component(pendulum)
    system.initialize(0.0)
    return system


def raw_bytes(samples: int, count: int) -> int:
    return samples * (8 + 4 + 3 * 8 * count)


def measure(case: str) -> dict[str, float]:
    gc.collect()
    system = pendulums(N_FMUS if case != "typo" else 1)
    before = resident_bytes()
    start = time.perf_counter()
    kept = []
    if case == "one run":
        kept.append(system.run(0.0, STEPS * DT, DT))
    elif case == "typo":
        try:
            system.run(0.0, 1.0, TYPO_DT, timeout=TYPO_SECONDS)
        except SimulationTimeoutError:
            pass
    else:
        per_chunk = STEPS // CHUNKS
        result = None
        for k in range(CHUNKS):
            result = system.run(k * per_chunk * DT, (k + 1) * per_chunk * DT, DT)
            if case == "all kept":
                kept.append(result)
        kept.append(result)
    wall = time.perf_counter() - start
    gc.collect()
    samples = len(system.get_history()["P0"][0])
    raw = raw_bytes(samples, N_FMUS if case != "typo" else 1)
    return {"wall": wall, "samples": samples, "raw": raw,
            "engine": system.history_bytes(), "rss": resident_bytes() - before}


def main() -> None:
    cases = ["one run", "chunks", "all kept", "typo"]
    figures = {case: measure(case) for case in cases}
    reference = figures["one run"]["wall"]
    print(f"{N_FMUS} pendulum_euler FMUs x {STEPS} steps of {DT} s ({CHUNKS} chunks); typo: "
          f"1 FMU, dt {TYPO_DT} over 1 s, timeout {TYPO_SECONDS} s\n")
    print("| case | samples | wall s | wall / one run | engine MB | engine / raw | "
          "RSS growth MB | RSS growth / raw |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for case in cases:
        f = figures[case]
        ratio = f"{f['wall'] / reference:.2f}" if case != "typo" else ""
        print(f"| {case} | {f['samples']} | {f['wall']:.3f} | {ratio} | {f['engine'] / 1e6:.1f} "
              f"| {f['engine'] / f['raw']:.3f} | {f['rss'] / 1e6:.1f} | "
              f"{f['rss'] / f['raw']:.3f} |")
    typo = figures["typo"]
    print(f"\ntypo: the whole grid would take {(10**9 + 1) * SAMPLE_BYTES / 1e9:.0f} GB; "
          f"{typo['samples']} samples recorded in {TYPO_SECONDS} s")


if __name__ == "__main__":
    main()
