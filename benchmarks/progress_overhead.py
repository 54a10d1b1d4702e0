"""What System.run(progress=...) costs: run time with and without progress, as ratios in one run.

One torsion_spring FMU (the cheapest bundled FMU: a doStep is a few multiplications, so any
per-step cost would show), plain FMUComponent, dt 1e-5 over --tf seconds of simulated time.
Three variants, interleaved, best of --repeat runs each:

  none      run(t0, tf, dt)
  callback  run(..., progress=callback): a Python function counting its calls
  bar       run(..., progress=True): the tqdm bar (drawn on stderr once a run lasts a second)

Progress is reported by the engine's monitor, about every 50 ms of wall time, so the callback
is called a handful of times per run, not once per step.

    python benchmarks/progress_overhead.py [--tf S] [--repeat N]
"""

from __future__ import annotations

import argparse
import time

from syssimx import FMUComponent, System, fmus

DT = 1e-5


def spring_system() -> System:
    spring = FMUComponent("Spring", fmus.path("torsion_spring"))
    spring.set_parameters(k=100.0, d=1.0)
    system = System("progress overhead")
    system.add_component(spring)
    return system


def timed_run(system: System, tf: float, progress: object) -> float:
    system.initialize(0.0)
    start = time.perf_counter()
    system.run(0.0, tf, DT, progress=progress)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tf", type=float, default=30.0, help="simulated seconds (default 30)")
    parser.add_argument("--repeat", type=int, default=7, help="runs per variant (default 7)")
    args = parser.parse_args()

    calls = 0

    def count(_t: float, _tf: float) -> None:
        nonlocal calls
        calls += 1

    system = spring_system()
    variants = {"none": None, "callback": count, "bar": True}
    best = dict.fromkeys(variants, float("inf"))
    timed_run(system, args.tf / 10, None)  # warm-up: libraries loaded, caches filled
    for _ in range(args.repeat):
        for name, progress in variants.items():
            best[name] = min(best[name], timed_run(system, args.tf, progress))
    steps = round(args.tf / DT)
    calls_per_run = calls / args.repeat
    print(f"{steps} macro steps of one torsion_spring FMU, best of {args.repeat} runs each")
    print(f"  none      {best['none']:.3f} s  ({1e9 * best['none'] / steps:.0f} ns per step)")
    print(f"  callback  {best['callback']:.3f} s  ratio {best['callback'] / best['none']:.3f}  "
          f"({calls_per_run:.0f} calls per run)")
    print(f"  bar       {best['bar']:.3f} s  ratio {best['bar'] / best['none']:.3f}")


if __name__ == "__main__":
    main()
