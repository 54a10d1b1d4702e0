"""Python-driven System against the bare C loop and SysSimX 0.4.3, as ratios in one run.

1 and 100 pendulum_euler FMUs (theta0 0.5, default Euler step 1e-4 inside each doStep),
plain FMUComponent, Gauss-Seidel, no events, dt 1e-3. The pendulums are uncoupled: their
outputs (rad, rad/s, rad/s2) cannot drive their torque input (N.m), which our System rejects
as incompatible units, and a chain through 99 extra adapter FMUs would no longer compare with
the engine benchmark's loop. Every step still sets each torque input and reads three outputs.

  ours     wall time of System.run through the Python API (best of --repeat runs)
  C loop   the engine benchmark executable <build>/tests/c/engine/engine_overhead, run with the
           same FMU count and dt and parsed: fmi2DoStep alone, fmi2DoStep with the torque set
           and the outputs read, and the engine's ssx_run called from C (best of its repeats)
  SysSimX  the SysSimX 0.4.3 package from PyPI with fmpy on the same FMUs, in the virtual
           environment seed_scenario.py creates (child process, PYTHONPATH removed). With 100
           FMUs it runs --syssimx-steps macro steps (default 1 000), compared with ours at the
           same step count; nothing is scaled.

Then the history of 100 FMUs x 3 outputs x 100 000 steps (fresh child process): the engine's
bytes (System.history_bytes) against the raw float64 size, and the peak RSS growth.

    python benchmarks/coupled_overhead.py [--repeat N] [--syssimx-steps N] [--no-syssimx]
"""

from __future__ import annotations

import argparse
import gc
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from seed_scenario import SYSSIMX_VERSION, syssimx_environment
from syssimx import FMUComponent, GaussSeidelAlgorithm, System, fmus
from syssimx._paths import build_dir

DT = 1e-3
STEPS = 10_000
MEMORY_FMUS, MEMORY_STEPS = 100, 100_000
MEMORY_TARGET = 1.2
HERE = Path(__file__).resolve().parent
C_LINE = re.compile(r"(\d+) FMU\(s\) x (\d+) steps of (\S+) s(?: \([^)]*\))?: "
                    r"bare doStep ([\d.]+) ms, "
                    r"bare doStep\+set\+get ([\d.]+) ms, engine ([\d.]+) ms")


def pendulums(count: int) -> System:
    system = System(f"{count} pendulums")
    for i in range(count):
        pendulum = FMUComponent(f"P{i}", fmus.path("pendulum_euler"))
        pendulum.set_parameters(theta0=0.5, omega0=0.0)
        system.add_component(pendulum)
    system.set_algorithm(GaussSeidelAlgorithm())
    system.initialize(0.0)
    return system


def loaded_binary_copies() -> int:
    """Distinct executable mappings of the pendulum binary in this process (Linux)."""
    maps = Path("/proc/self/maps").read_text().splitlines()
    return len({line.split()[-1] for line in maps
                if "r-xp" in line and line.endswith("pendulum_euler.so")})


def run_ours_once(count: int, steps: int) -> dict[str, Any]:
    gc.collect()  # earlier systems sit in reference cycles: unload their FMUs first
    system = pendulums(count)
    copies = loaded_binary_copies()
    start = time.perf_counter()
    result = system.run(0.0, steps * DT, DT)
    wall = time.perf_counter() - start
    final = [float(result[f"P{i}"][1]["theta"][-1]) for i in (0, count - 1)]
    return {"wall": wall, "final_theta": final, "binary_copies": copies}


def measure_ours(count: int, steps: int, repeat: int) -> dict[str, Any]:
    runs = [run_ours_once(count, steps) for _ in range(repeat)]
    return min(runs, key=lambda run: run["wall"])


def measure_c_loop(count: int, repeat: int) -> dict[str, float] | str:
    build = build_dir()
    if build is None:
        return "SYSSIMX_BUILD_DIR not set: no meson build to take engine_overhead from"
    executable = build / "tests" / "c" / "engine" / "engine_overhead"
    if not executable.exists():
        return f"{executable.name} not built"
    run = subprocess.run([str(executable), str(count), repr(DT), str(repeat)],
                         capture_output=True, text=True)
    match = C_LINE.search(run.stdout)
    if run.returncode != 0 or match is None:
        return f"{executable.name} failed or printed an unknown format: {run.stderr.strip()}"
    if (int(match[1]), int(match[2]), float(match[3])) != (count, STEPS, DT):
        return f"{executable.name} measured a different case: {match[0]}"
    return {"bare": float(match[4]) / 1e3, "bare_io": float(match[5]) / 1e3,
            "engine": float(match[6]) / 1e3}


def measure_syssimx(count: int, steps: int, repeat: int) -> dict[str, Any]:
    python = syssimx_environment()
    environment = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    run = subprocess.run([str(python), str(HERE / "coupled_syssimx_child.py"),
                          fmus.path("pendulum_euler"), str(count), str(steps), repr(DT),
                          str(repeat)], capture_output=True, text=True, env=environment)
    if run.returncode != 0:
        return {"error": run.stderr.strip().splitlines()[-1]}
    return json.loads(run.stdout.strip().splitlines()[-1])


def measure_history_memory() -> dict[str, int]:
    run = subprocess.run([sys.executable, str(HERE / "coupled_history_memory.py"),
                          str(MEMORY_FMUS), str(MEMORY_STEPS), repr(DT)],
                         capture_output=True, text=True, check=True)
    return json.loads(run.stdout.strip().splitlines()[-1])


def per_step_us(wall: float, count: int, steps: int) -> str:
    return f"{wall / (count * steps) * 1e6:.3f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per case (best taken)")
    parser.add_argument("--syssimx-steps", type=int, default=1_000,
                        help="macro steps for SysSimX with 100 FMUs")
    parser.add_argument("--syssimx-repeat", type=int, default=1)
    parser.add_argument("--no-syssimx", action="store_true", help="skip the PyPI SysSimX run")
    args = parser.parse_args()

    rows = []  # (FMUs, steps, path, wall s, wall s of ours at the same size or None)
    notes = []
    for count in (1, 100):
        ours = measure_ours(count, STEPS, args.repeat)
        rows.append((count, STEPS, "ours: System.run (Python)", ours["wall"], None))
        notes.append(f"ours, {count} FMU(s): FMU binary copies mapped: {ours['binary_copies']} "
                     "(components of one FMU file share its extraction), as in the C loop")
        c_loop = measure_c_loop(count, args.repeat)
        if isinstance(c_loop, str):
            notes.append(f"C loop, {count} FMU(s): {c_loop}")
        else:
            for key, label in (("bare", "C: bare fmi2DoStep loop"),
                               ("bare_io", "C: bare doStep+set+get loop"),
                               ("engine", "C: ssx_run from C")):
                rows.append((count, STEPS, label, c_loop[key], ours["wall"]))
        if args.no_syssimx:
            continue
        steps = STEPS if count == 1 else args.syssimx_steps
        reference = ours if steps == STEPS else measure_ours(count, steps, args.repeat)
        if steps != STEPS:
            rows.append((count, steps, "ours: System.run (Python)", reference["wall"], None))
        theirs = measure_syssimx(count, steps, args.syssimx_repeat)
        if "error" in theirs:
            notes.append(f"SysSimX {SYSSIMX_VERSION}, {count} FMU(s): {theirs['error']}")
            continue
        rows.append((count, steps, f"SysSimX {SYSSIMX_VERSION} (fmpy)", theirs["wall"],
                     reference["wall"]))
        difference = max(abs(a - b) for a, b in zip(theirs["final_theta"],
                                                     reference["final_theta"], strict=True))
        notes.append(f"{count} FMU(s), {steps} steps: final theta ours "
                     f"{reference['final_theta'][0]:.15g}, |SysSimX - ours| = {difference:.1e}")
        if steps != STEPS:
            notes.append(f"SysSimX with {count} FMUs ran {steps} steps, not {STEPS}; its ratio "
                         f"is against ours at {steps} steps (no scaling)")

    memory = measure_history_memory()
    print(f"pendulum_euler FMUs, Gauss-Seidel, no events, dt {DT}; best of {args.repeat} runs "
          f"(SysSimX: best of {args.syssimx_repeat}); ratio = this path's wall / ours\n")
    print("| FMUs | steps | path | wall ms | us per FMU step | ratio to ours |")
    print("|---:|---:|---|---:|---:|---:|")
    for count, steps, label, wall, reference in rows:
        ratio = f"{wall / reference:.3g}" if reference is not None else "1"
        print(f"| {count} | {steps} | {label} | {wall * 1e3:.2f} | "
              f"{per_step_us(wall, count, steps)} | {ratio} |")
    engine, raw = memory["engine_bytes"], memory["raw_bytes"]
    growth = memory["rss_growth_bytes"]
    print(f"\nhistory of {MEMORY_FMUS} FMUs x 3 outputs x {MEMORY_STEPS} steps "
          f"({memory['samples']} samples; raw = samples x (3 x {MEMORY_FMUS} + 1 time) x 8 B), "
          f"target within {MEMORY_TARGET}x raw\n")
    print("| figure | MB | ratio to raw float64 | within target |")
    print("|---|---:|---:|---|")
    print(f"| raw float64 | {raw / 1e6:.1f} | 1 | |")
    for label, value in (("engine (ssx_history_bytes)", engine), ("peak RSS growth", growth)):
        within = "yes" if value <= MEMORY_TARGET * raw else "no"
        print(f"| {label} | {value / 1e6:.1f} | {value / raw:.3f} | {within} |")
    if notes:
        print()
        for note in notes:
            print(f"- {note}")


if __name__ == "__main__":
    main()
