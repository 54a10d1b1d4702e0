"""What a clock tick costs: the clocked controller (sampled_pi_controller_fmi3, its input clock
`sample` ticking every 0.1 s) run by syssimx, against the plain controller (pi_controller_fmi3,
no clock, its integral a continuous state) stepped at the sample time, in one run; each alone
in its system, its inputs held (setpoint 0.5, measurement 0.25).

Printed per case: sample periods per CPU second (CPU time: the machine may be shared) and the
ratio to the plain controller with euler_step_size = 0.1, which then takes one Euler step per
sample period: the same forward-Euler PI law as the clocked one. The plain controller at its
default euler_step_size (1e-4 s) is shown too. The clocked cases: dt = 0.1 (a tick at each
communication point: enterEventMode, fmi3SetClock, fmi3UpdateDiscreteStates, enterStepMode
beside the doStep) and dt = 0.5 (five ticks inside each step: the controller's doStep is cut
at each, the system's step is not); and the clocked controller as Model Exchange, dt = 0.5 (the
engine stops at each tick as at a time event: enterEventMode, fmi3SetClock,
fmi3UpdateDiscreteStates, enterContinuousTimeMode).

    python benchmarks/clocked_controller.py [--ticks 20000] [--repeats 3]
"""

from __future__ import annotations

import argparse
import statistics
import time

from syssimx import FMUComponent, System, fmus

PERIOD = 0.1  # the clock's intervalDecimal


def alone(controller_fmu: str, euler_step: float | None = None,
          interface: str = "co-simulation") -> System:
    controller = FMUComponent("PI", fmus.path(controller_fmu), interface=interface)
    if euler_step is not None:
        controller.set_parameters(euler_step_size=euler_step)
    controller.set_inputs({"setpoint": 0.5, "measurement": 0.25})
    system = System(controller_fmu)
    system.add_component(controller)
    return system


def ticks_per_second(controller_fmu: str, dt: float, ticks: int, repeats: int,
                     euler_step: float | None = None,
                     interface: str = "co-simulation") -> float:
    """Median over `repeats` runs of sample periods per CPU second."""
    rates = []
    for _ in range(repeats):
        system = alone(controller_fmu, euler_step, interface)
        system.initialize(0.0)
        start = time.process_time()
        system.run(0.0, ticks * PERIOD, dt, keep_history=False)
        rates.append(ticks / (time.process_time() - start))
    return statistics.median(rates)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ticks", type=int, default=20_000)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    clocked = "sampled_pi_controller_fmi3"
    cases = [("plain, euler_step_size 0.1, dt = 0.1", "pi_controller_fmi3", PERIOD, PERIOD,
              "co-simulation"),
             ("plain, euler_step_size 1e-4, dt = 0.1", "pi_controller_fmi3", PERIOD, None,
              "co-simulation"),
             ("clocked, dt = 0.1 (a tick per step)", clocked, PERIOD, None, "co-simulation"),
             ("clocked, dt = 0.5 (5 ticks per step)", clocked, 0.5, None, "co-simulation"),
             ("clocked, Model Exchange, dt = 0.5", clocked, 0.5, None, "model-exchange")]
    base = None
    print(f"{args.ticks} sample periods of {PERIOD} s, median of {args.repeats}")
    for label, fmu, dt, euler_step, interface in cases:
        rate = ticks_per_second(fmu, dt, args.ticks, args.repeats, euler_step, interface)
        base = base or rate
        print(f"  {label:40s} {rate:12.0f} per s   x{rate / base:.2f}")


if __name__ == "__main__":
    main()
