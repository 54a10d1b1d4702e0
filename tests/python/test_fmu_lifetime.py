"""An FMUComponent's end of life: finalizers that never wait for cffi's lock, and a clear
error for every use after free()."""

from __future__ import annotations

import re
import subprocess
import sys
import textwrap

import pytest
from syssimx import FMUComponent, System, fmus
from syssimx.errors import ConfigurationError, FMUError

FREED = re.escape("P: the FMU was released by FMUComponent.free(); create a new FMUComponent "
                  "to use it again")

# Collections at nearly every allocation: a component dropped in a reference cycle is finalized
# somewhere inside the cffi calls of construction, initialize and run, also while cffi holds
# the lock a first lookup of a library function takes.
GC_EVERYWHERE = textwrap.dedent("""
    import gc
    gc.set_threshold(1)
    from syssimx import FMUComponent, System, fmus
    for _ in range(3):
        dropped = FMUComponent("dropped", fmus.path("pendulum_euler"))
        state = dropped.instance
        del dropped
        system = System("s")
        pendulum = FMUComponent("P", fmus.path("pendulum_cvode"))
        pendulum.set_parameters(theta0=0.5)
        system.add_component(pendulum)
        system.initialize(0.0)
        pendulum.instance.getFMUstate()  # dropped at once: finalized during the run
        result = system.run(0.0, 0.2, 0.05)
        del system, pendulum, result
    gc.set_threshold(700)
    print("done")
""")


def test_finalizers_run_inside_cffi_calls_without_hanging():
    done = subprocess.run([sys.executable, "-c", GC_EVERYWHERE], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "done"


@pytest.fixture
def freed() -> FMUComponent:
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    system = System("s")
    system.add_component(pendulum)
    system.initialize(0.0)
    system.run(0.0, 0.1, 0.05)
    pendulum.free()
    return pendulum


def test_initialize_after_free_is_an_error(freed: FMUComponent):
    system = System("again")
    system.add_component(freed)
    with pytest.raises(FMUError, match=FREED):
        system.initialize(0.0)
    with pytest.raises(FMUError, match=FREED):
        freed.initialize(0.0)


def test_counters_after_free_is_an_error(freed: FMUComponent):
    with pytest.raises(FMUError, match=FREED):
        freed.instance.counters()


def test_get_state_after_free_is_an_error(freed: FMUComponent):
    with pytest.raises(FMUError, match=FREED):
        freed.get_state()


@pytest.mark.parametrize("call", [
    lambda p: p.instance.instantiate(),
    lambda p: p.instance.getReal([0]),
    lambda p: p.instance.setReal([0], [1.0]),
    lambda p: p.instance.doStep(0.0, 0.1),
    lambda p: p.instance.getFMUstate(),
    lambda p: p.reinitialize(0.0),
])
def test_every_fmu_call_after_free_is_an_error(freed: FMUComponent, call):
    with pytest.raises(FMUError, match=FREED):
        call(freed)


def test_stepping_a_freed_component_on_its_own_asks_for_initialize(freed: FMUComponent):
    with pytest.raises(ConfigurationError, match=re.escape("P (standalone): call "
                                                           "initialize(t0) before run()")):
        freed.do_step(0.0, 0.1)


def test_free_twice_and_states_of_a_freed_fmu_are_harmless():
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.initialize(0.0)
    state = pendulum.instance.getFMUstate()
    pendulum.free()
    pendulum.free()
    state.free()  # released with the instance: nothing left to free
    assert pendulum.instance.released()
