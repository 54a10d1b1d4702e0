"""The System a worker process keeps from one member of an ensemble to the next.

Building a System (reading model descriptions, loading FMUs, making components, and often an
initialize the member does again) was 40% of a seed-scenario member's time. A worker builds
it once per ensemble instead, and for each member sets the member's parameters on it and
initializes it again: System.initialize starts every run from scratch (each FMU instance reset
to its start values, a fresh history) on the engine plan it compiled for the first member.

What a member could leave behind is in its components' user values: the parameters and inputs
that initialize writes. Every member of an ensemble sets the same names, so the next member
overwrites what this one set; what the run itself changed (a handler calling set_parameters) is
caught by comparing those values before and after the run, and that System is not kept. Only
Systems made of syssimx's own component classes are kept: a class of the user's may hold state
of its own that no comparison sees (a MultiComponent's models included). A failed member's
System is never kept (an FMU may refuse every call after fmi2Fatal). Code the user runs during a
member (handlers, indicator functions) sees the same Python objects from member to member, as in
a loop that initializes one System again and again; the system function runs once per worker and
ensemble. A worker forked from a process that kept a System does not take it: its FMU
instances and folders are the parent's. It keeps it unused instead of dropping it (dropping it
would free what belongs to the parent, e.g. an isolated component's host process).

On a kept System whose components the engine starts by itself (system/member_runs.py), a
member after the first is one engine call: its values written into the start values the
previous member's initialize wrote, no set_parameters, initialize or run in Python; the
histories, events and statistics are the same, bit for bit.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from typing import Any

from ..components.fmu import FMUComponent
from ..components.multi import MultiComponent
from ..errors import ConfigurationError
from ..system.member_runs import (
    EngineMembers,
    engine_runs_members,
    engine_writes_exactly,
    split_member_names,
)
from ..system.system import System
from .system_source import SystemSource

UserValues = list[tuple[str, dict[str, Any], tuple[str, ...], tuple[Any, ...]]]


class ReusedSystem:
    """The one System this process keeps, and the ensemble it belongs to."""

    def __init__(self) -> None:
        self._ensemble: str | None = None
        self._system: System | None = None
        self._taken: System | None = None  # the kept System take gave out last
        # the engine's members of the kept System, by the parameter names they write
        self._members: tuple[System, tuple[str, ...], EngineMembers | None] | None = None
        self._parents: list[System] = []  # kept by the parent before a fork: never used
        os.register_at_fork(after_in_child=self._set_aside_parents)

    def _set_aside_parents(self) -> None:
        if self._system is not None:
            self._parents.append(self._system)
        self._system = self._ensemble = self._taken = self._members = None

    def take(self, ensemble: str | None, build: SystemSource) -> System:
        """The System kept for `ensemble`, else a fresh one from `build` (always fresh for no
        ensemble). A System kept for another ensemble is dropped; until the one taken is
        given back, nothing is kept."""
        if ensemble is None:
            return _built(build)
        system, kept_for = self._system, self._ensemble
        self._system = self._ensemble = None
        self._taken = system if system is not None and kept_for == ensemble else None
        if self._taken is None:
            self._members = None
            return _built(build)
        return self._taken

    def engine_members(self, system: System, parameters: Mapping[str, Any]
                       ) -> EngineMembers | None:
        """The engine's members of `system`, when take gave it out as kept (the previous
        member of its ensemble initialized it with the same names set) and the engine can
        run them: every name a parameter it writes (member_runs.engine_runs_members), every
        value one set_parameters takes as it is (engine_writes_exactly). Made on first use,
        kept with the System."""
        if system is not self._taken or system._plan is None:
            return None
        names = tuple(parameters)
        if any(name.partition(".")[0] not in system.components or not name.partition(".")[2]
               for name in names):
            return None  # the member's own path names what is wrong
        split = split_member_names(system, names)
        if self._members is None or self._members[:2] != (system, names) or \
                (self._members[2] is not None and self._members[2].plan is not system._plan):
            members = EngineMembers(system, split) if engine_runs_members(system, split) \
                else None
            self._members = (system, names, members)
        members = self._members[2]
        if members is None or not engine_writes_exactly(system, split, list(
                parameters.values())):
            return None
        return members

    def give_back(self, ensemble: str | None, system: System, before_run: UserValues) -> None:
        """After a member that succeeded: keep `system` for the next member of `ensemble` when
        its run left the user values as they were before it (`before_run`, user_values)."""
        if ensemble is None or not reusable(system) or user_values(system) != before_run:
            return
        # kept as it is: the next member's initialize resets the FMU instances in place
        self._ensemble, self._system = ensemble, system


def reusable(system: System) -> bool:
    """Whether every component, and every model of a MultiComponent, is of a syssimx class
    (whose state initialize resets)."""
    components = list(system.components.values())
    components += [model for component in components if isinstance(component, MultiComponent)
                   for model in component.models.values()]
    return all(type(component).__module__.split(".")[0] == "syssimx"
               for component in components)


def user_values(system: System) -> UserValues:
    """Per component what initialize writes: the parameters, the names of those written to an
    FMU, and the inputs' start values (NaN, an input the FMU keeps its own value of, as
    None: NaN equals nothing)."""
    return [(name, dict(component.parameters),
             tuple(sorted(component.user_parameters()))
             if isinstance(component, FMUComponent) else (),
             tuple(_comparable(component.input_start(port))
                   for port in component.engine_inputs()))
            for name, component in system.components.items()]


def _built(build: SystemSource) -> System:
    system = build()
    if not isinstance(system, System):
        raise ConfigurationError(f"the system function returned {type(system).__name__}, "
                                 "not a System")
    return system


def _comparable(value: float) -> float | None:
    return None if math.isnan(value) else value


reused_system = ReusedSystem()
