"""Cost of fmi2DoStep (dt = 1e-3) and of FMU state snapshots for every FMU of a meson build.

Runs the compiled fmu_step_cost program on each FMU binary and prints a Markdown table, with
the step cost as a ratio to the Euler pendulum measured in the same run.

Usage: python benchmarks/fmu_step_cost.py [meson build directory]
       (default: $SYSSIMX_BUILD_DIR, else build/release)
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

# Start values that make each run representative: a swinging pendulum, a model that never fails.
STARTS = {
    "pendulum_euler": ["theta0=0.5"],
    "pendulum_cvode": ["theta0=0.5"],
    "pendulum_contact_euler": ["theta0=0.5"],
    "pendulum_contact_cvode": ["theta0=0.5"],
    "failing": ["fail_time=1e9"],
}
BASELINE = "pendulum_euler"


def measure(build: Path, stem: str) -> tuple[float, int, float, float]:
    program = build / "tests" / "c" / "fmu" / "fmu_step_cost"
    models = build / "models"
    args = [str(program), str(models / f"{stem}.so"), str(models / f"{stem}_modelDescription.xml")]
    output = subprocess.run(
        args + STARTS.get(stem, []), check=True, capture_output=True, text=True
    ).stdout.split()
    step, size, get, set_ = output
    return float(step), int(size), float(get), float(set_)


def main(argv: list[str]) -> int:
    default = os.environ.get("SYSSIMX_BUILD_DIR", "build/release")
    build = Path(argv[1] if len(argv) > 1 else default).resolve()
    # the FMI 2.0 builds: the measuring program is an FMI 2.0 master
    stems = sorted(p.stem for p in (build / "models").glob("*.fmu") if not p.stem.endswith("_fmi3"))
    if not stems:
        print(f"no FMUs in {build / 'models'}; build first (meson compile -C {build})")
        return 1
    results = {stem: measure(build, stem) for stem in stems}
    baseline = results[BASELINE][0] if BASELINE in results else None
    print(
        "| FMU | ns per doStep (dt 1e-3) | ratio to pendulum_euler | state bytes "
        "| ns per get state | ns per set state |"
    )
    print("|---|---:|---:|---:|---:|---:|")
    for stem, (step, size, get, set_) in results.items():
        ratio = f"{step / baseline:.2f}" if baseline else "-"
        print(f"| {stem} | {step:.0f} | {ratio} | {size} | {get:.0f} | {set_:.0f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
