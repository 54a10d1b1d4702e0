"""Decimation: history memory and run time of one system recorded at output intervals 1, 10
and 100, measured side by side in one process.

N pendulum_euler FMUs x 3 outputs, STEPS macro steps of DT through the Python System; each
interval runs on a freshly initialized system, best of REPEAT runs. Prints per interval the
samples kept, the engine's history bytes (System.history_bytes) and the wall time, with ratios
to interval 1. Then the run form with FMPy's meaning, run(t0, tf, dt, output_interval=k*dt):
one pendulum, LONG_STEPS steps keeping every LONG_STEPS/KEPT-th, against the same run keeping
all.

    python benchmarks/output_interval.py [--fmus 10] [--steps 100000] [--dt 1e-3] [--repeat 3]
        [--long-steps 1000000] [--kept 1000]
"""

from __future__ import annotations

import argparse
import time

from syssimx import FMUComponent, System, fmus

INTERVALS = (1, 10, 100)


def pendulums(count: int) -> System:
    system = System("decimation")
    for i in range(count):
        pendulum = FMUComponent(f"P{i}", fmus.path("pendulum_euler"))
        pendulum.set_parameters(theta0=0.5, omega0=0.0)
        system.add_component(pendulum)
    return system


def measure(system: System, interval: int, steps: int, dt: float) -> tuple[int, int, float]:
    """Samples kept, history bytes and wall seconds of one run from t0 = 0."""
    system.initialize(0.0, output_interval=interval)
    start = time.perf_counter()
    result = system.run(0.0, steps * dt, dt)
    wall = time.perf_counter() - start
    return len(result.micro), system.history_bytes(), wall


def measure_run_form(steps: int, kept: int, dt: float, decimated: bool
                     ) -> tuple[int, int, float]:
    """Samples kept, history bytes and wall seconds of one pendulum run of `steps` steps,
    with run(output_interval=) keeping `kept` of them or without it."""
    system = pendulums(1)
    system.initialize(0.0)
    interval = steps // kept * dt if decimated else None
    start = time.perf_counter()
    result = system.run(0.0, steps * dt, dt, output_interval=interval)
    wall = time.perf_counter() - start
    return len(result.micro), system.history_bytes(), wall


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fmus", type=int, default=10)
    parser.add_argument("--steps", type=int, default=100_000)
    parser.add_argument("--dt", type=float, default=1e-3)
    parser.add_argument("--repeat", type=int, default=3, help="runs per interval (best taken)")
    parser.add_argument("--long-steps", type=int, default=1_000_000)
    parser.add_argument("--kept", type=int, default=1000)
    args = parser.parse_args()
    system = pendulums(args.fmus)
    best: dict[int, tuple[int, int, float]] = {}
    for _ in range(args.repeat):
        for interval in INTERVALS:  # interleaved: a drift of the machine hits every interval
            samples, history, wall = measure(system, interval, args.steps, args.dt)
            if interval not in best or wall < best[interval][2]:
                best[interval] = (samples, history, wall)
    print(f"{args.fmus} pendulum_euler FMUs x {args.steps} steps of {args.dt} s")
    print(f"{'interval':>8} {'samples':>9} {'history MB':>11} {'memory ratio':>13} "
          f"{'wall s':>8} {'wall ratio':>11}")
    _, full_bytes, full_wall = best[1]
    for interval in INTERVALS:
        samples, history, wall = best[interval]
        print(f"{interval:>8} {samples:>9} {history / 1e6:>11.2f} {history / full_bytes:>13.3f} "
              f"{wall:>8.3f} {wall / full_wall:>11.2f}")

    runs = {decimated: min((measure_run_form(args.long_steps, args.kept, args.dt, decimated)
                            for _ in range(args.repeat)), key=lambda measured: measured[2])
            for decimated in (False, True)}
    (all_samples, all_bytes, all_wall), (kept_samples, kept_bytes, kept_wall) = runs.values()
    print(f"\n1 pendulum_euler FMU, {args.long_steps} steps of {args.dt} s, run(..., "
          f"output_interval={args.long_steps // args.kept} * dt)")
    print(f"{'':>20} {'samples':>9} {'history MB':>11} {'wall s':>8}")
    print(f"{'every step':>20} {all_samples:>9} {all_bytes / 1e6:>11.3f} {all_wall:>8.3f}")
    print(f"{'output_interval':>20} {kept_samples:>9} {kept_bytes / 1e6:>11.3f} "
          f"{kept_wall:>8.3f}")
    print(f"history memory: {all_bytes / kept_bytes:.0f}x less; wall time ratio "
          f"{kept_wall / all_wall:.2f}")


if __name__ == "__main__":
    main()
