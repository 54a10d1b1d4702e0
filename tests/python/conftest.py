"""Shared fixtures: the bundled FMUs opened with fmpy, an FMI client independent of syssimx."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

import pytest
from fixture_fmus import fmu_path
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE
from fmpy.model_description import ScalarVariable


@dataclass
class OpenFMU:
    """An fmpy slave of a bundled FMU, with its variables by name and the messages it logged."""

    slave: FMU2Slave
    variables: dict[str, ScalarVariable]
    messages: list[tuple[int, str]] = field(default_factory=list)
    callbacks: fmi2CallbackFunctions | None = None  # keeps fmpy's logger callback alive

    def vr(self, name: str) -> int:
        return self.variables[name].valueReference

    def get(self, name: str) -> float:
        variable = self.variables[name]
        if variable.type == "Boolean":
            return float(self.slave.getBoolean([variable.valueReference])[0])
        if variable.type == "Integer":
            return float(self.slave.getInteger([variable.valueReference])[0])
        return self.slave.getReal([variable.valueReference])[0]

    def set(self, name: str, value: float) -> None:
        variable = self.variables[name]
        if variable.type == "Integer":
            self.slave.setInteger([variable.valueReference], [int(value)])
        elif variable.type == "Boolean":
            self.slave.setBoolean([variable.valueReference], [bool(value)])
        else:
            self.slave.setReal([variable.valueReference], [float(value)])


OpenFunction = Callable[..., OpenFMU]


@pytest.fixture
def open_fmu(tmp_path) -> Iterator[OpenFunction]:
    """open_fmu(name, starts={...}, tolerance=None, start_time=0.0, initialize=True, guid=None)
    instantiates a bundled FMU (logging on), sets it up and initializes it with the start
    values. Instances are freed after the test."""
    opened: list[OpenFMU] = []

    def open_one(
        name: str,
        starts: dict[str, float] | None = None,
        tolerance: float | None = None,
        start_time: float = 0.0,
        initialize: bool = True,
        guid: str | None = None,
    ) -> OpenFMU:
        path = fmu_path(name)
        description = read_model_description(path)
        unzipped = extract(path, unzipdir=tmp_path / f"{name}-{len(opened)}")
        slave = FMU2Slave(
            guid=guid or description.guid,
            unzipDirectory=unzipped,
            modelIdentifier=description.coSimulation.modelIdentifier,
            instanceName=name,
        )
        fmu = OpenFMU(slave, {v.name: v for v in description.modelVariables})

        def record(environment, instance, status, category, message) -> None:
            fmu.messages.append((status, message.decode()))

        callbacks = fmi2CallbackFunctions()
        callbacks.logger = fmi2CallbackLoggerTYPE(record)
        fmu.callbacks = callbacks
        slave.instantiate(callbacks=callbacks, loggingOn=True)
        opened.append(fmu)
        if initialize:
            slave.setupExperiment(tolerance=tolerance, startTime=start_time)
            slave.enterInitializationMode()
            for variable, value in (starts or {}).items():
                fmu.set(variable, value)
            slave.exitInitializationMode()
        return fmu

    yield open_one
    for fmu in opened:
        fmu.slave.freeInstance()


def first_time(
    fmu: OpenFMU,
    t_from: float,
    dt: float,
    t_max: float,
    holds: Callable[[OpenFMU], bool],
    resolution: float = 1e-12,
) -> tuple[float, float]:
    """The first time after t_from at which holds(fmu) is true: step by dt, then bisect the step
    length over a saved FMU state. Returns (time, t_now); the FMU is left just past it, at t_now."""
    k = 0
    while True:
        t = t_from + k * dt
        assert t < t_max, "the condition never held"
        state = fmu.slave.getFMUState()
        fmu.slave.doStep(t, dt)
        if not holds(fmu):
            fmu.slave.freeFMUState(state)
            k += 1
            continue
        low, high = 0.0, dt
        while high - low > resolution:
            middle = 0.5 * (low + high)
            fmu.slave.setFMUState(state)
            fmu.slave.doStep(t, middle)
            if holds(fmu):
                high = middle
            else:
                low = middle
        fmu.slave.setFMUState(state)
        fmu.slave.doStep(t, high)
        fmu.slave.freeFMUState(state)
        return t + 0.5 * (low + high), t + high


@pytest.fixture
def find_time() -> Callable[..., tuple[float, float]]:
    """first_time(fmu, t_from, dt, t_max, holds, resolution) as a fixture."""
    return first_time
