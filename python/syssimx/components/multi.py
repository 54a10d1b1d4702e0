"""MultiComponent: one component that switches between interchangeable models at events.

The wrapper keeps its ports and connections; underneath, one model (a "mode") is active and
is stepped. `set_switch_regions` turns each boundary of a SwitchRegions map into an event
indicator of the wrapper, so a switch is located by the hybrid algorithm like any event and
happens at the crossing instant, not on the grid. At a switch the active model's physical
state (`get_state`) is translated by `_adapt_state` (a subclass's job) and imported into the
incoming model (`set_state`, which restarts it at the switch time); the committed switch is
recorded as a ModeSwitchEvent (`switch_events`, `result.mode_switches`).

Each model runs on its own (an FMU is stepped by the engine through its own one-component
system); the wrapper is a Python component, so it costs one Python call per step.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from .. import units
from ..core.port import PortType
from ..errors import ConfigurationError
from ..units import conversion
from .base import CoSimComponent
from .switch_regions import RegionBoundary, SwitchRegions

logger = logging.getLogger("syssimx.multi")

REGION_EVENT = "region_boundary_{}"


@dataclass(frozen=True)
class ModeSwitchEvent:
    """One committed switch at `time` from `from_mode` to `to_mode`. The source state (as
    read) and the target state (after import) are kept when the wrapper's
    record_switch_state is true; transfer_report is what _build_transfer_report returned."""

    time: float
    from_mode: str
    to_mode: str
    source_state: dict[str, Any] | None = None
    target_state: dict[str, Any] | None = None
    transfer_report: Any = None


class MultiComponent(CoSimComponent):
    """A component whose model is one of `models`, starting with `initial_mode`.

    Every model has the initial model's ports (same names, types, compatible units). A
    subclass implements `_adapt_state(state, target_mode)`; switching is declared with
    `set_switch_regions` (or done by a handler with `_switch_mode(mode, t)`)."""

    def __init__(self, name: str, models: dict[str, CoSimComponent], initial_mode: str,
                 group: str | None = None) -> None:
        if not models:
            raise ConfigurationError(f"{name}: 'models' must not be empty")
        if initial_mode not in models:
            raise ConfigurationError(f"{name}: initial_mode {initial_mode!r} is not one of the "
                                     f"models {list(models)}")
        super().__init__(name, group=group)
        self.models = dict(models)
        self._initial_mode = initial_mode
        self._active_mode = initial_mode
        self._switch_regions: SwitchRegions | None = None
        self._boundaries: dict[str, RegionBoundary] = {}
        self.active_region_index: int | None = None
        self.record_switch_state = False
        self._switch_events: list[ModeSwitchEvent] = []
        # per mode, (scale, offset) from the wrapper's input units to the model's, and from
        # the model's output units to the wrapper's
        self._to_model: dict[str, dict[str, tuple[float, float]]] = {}
        self._from_model: dict[str, dict[str, tuple[float, float]]] = {}
        self._unify_ports()

    # ---------------------------------------------------------------- modes
    @property
    def active_mode(self) -> str:
        return self._active_mode

    @property
    def active_comp(self) -> CoSimComponent:
        return self.models[self._active_mode]

    @property
    def switch_regions(self) -> SwitchRegions | None:
        return self._switch_regions

    @property
    def switch_events(self) -> tuple[ModeSwitchEvent, ...]:
        """The switches committed since the last initialization, in order."""
        return tuple(self._switch_events)

    def _unify_ports(self) -> None:
        """The initial model's ports become the wrapper's; every model must have them."""
        reference = self.models[self._initial_mode]
        self.input_specs = dict(reference.input_specs)
        self.output_specs = {n: s for n, s in reference.output_specs.items()
                             if s.type != PortType.EVENT}
        for mode, model in self.models.items():
            self._to_model[mode], self._from_model[mode] = {}, {}
            for kind, specs, theirs in (("input", self.input_specs, model.input_specs),
                                        ("output", self.output_specs, model.output_specs)):
                for port, spec in specs.items():
                    other = theirs.get(port)
                    if other is None or other.type != spec.type:
                        raise ConfigurationError(
                            f"{self.name}: model {mode!r} has no {spec.type.name} {kind} "
                            f"{port!r} like model {self._initial_mode!r}")
                    if spec.type == PortType.EVENT:
                        continue
                    try:
                        if kind == "input":
                            self._to_model[mode][port] = conversion(spec.unit, other.unit)
                        else:
                            self._from_model[mode][port] = conversion(other.unit, spec.unit)
                    except units.DimensionalityError as exc:
                        raise ConfigurationError(
                            f"{self.name}: {kind} {port!r} of model {mode!r} has unit "
                            f"{other.unit!r}, not convertible to {spec.unit!r}") from exc
            for output, inputs in model.direct_feedthrough.items():
                if output in self.output_specs:
                    self.direct_feedthrough.setdefault(output, set()).update(
                        i for i in inputs if i in self.input_specs)

    def _adapt_state(self, state: dict[str, Any], target_mode: str) -> dict[str, Any]:
        """The active model's state (get_state) translated for model `target_mode`
        (its set_state). A subclass implements it; return `state` for identical models."""
        raise NotImplementedError(f"{self.name}: a MultiComponent subclass implements "
                                  "_adapt_state(state, target_mode)")

    def _build_transfer_report(self, source_state: dict[str, Any],
                               target_state: dict[str, Any], source_mode: str,
                               target_mode: str, t: float) -> Any:
        """Evidence of a transfer kept on its ModeSwitchEvent; may raise to refuse it."""
        return None

    # ---------------------------------------------------------------- regions
    def set_switch_regions(self, key: SwitchRegions | Callable[[Any], float],
                           breakpoints: Sequence[float] | None = None,
                           modes: Sequence[str] | None = None,
                           band: float | Sequence[float] | None = None) -> None:
        """Switch by region: a SwitchRegions, or its key, breakpoints, modes and band. Adds
        the indicator "region_boundary_<i>" (direction 0) per boundary."""
        if self._switch_regions is not None:
            raise ConfigurationError(f"{self.name}: switch regions are already declared")
        if isinstance(key, SwitchRegions):
            regions = key
        else:
            if breakpoints is None or modes is None or band is None:
                raise ConfigurationError(f"{self.name}: set_switch_regions needs a "
                                         "SwitchRegions or key, breakpoints, modes and band")
            regions = SwitchRegions(key, breakpoints, modes, band)
        unknown = sorted(set(regions.modes) - set(self.models))
        if unknown:
            raise ConfigurationError(f"{self.name}: regions name unknown models {unknown}; "
                                     f"models: {list(self.models)}")
        stuck = sorted(m for m in set(regions.modes) if not self.models[m].can_rollback())
        if stuck:
            raise ConfigurationError(f"{self.name}: models {stuck} cannot roll back, which "
                                     "locating a region crossing needs")
        for boundary in regions.boundaries:
            event = REGION_EVENT.format(boundary.index)
            self.add_event_indicator(event, self._boundary_indicator(regions, boundary))
            self._boundaries[event] = boundary
        self._switch_regions = regions

    def _boundary_indicator(self, regions: SwitchRegions, boundary: RegionBoundary
                            ) -> Callable[[Any], float]:
        def indicator(wrapper: Any) -> float:
            return float(regions.key(wrapper)) - boundary.threshold_for(
                wrapper.active_region_index)
        return indicator

    def self_handled_events(self) -> list[str]:
        return list(self._boundaries)

    # ---------------------------------------------------------------- life cycle
    def _initialize_component(self, t0: float) -> None:
        """Every model starts at t0 (each ready to take over); the region holding the key's
        value picks the active one."""
        self._switch_events = []
        self._active_mode = self._initial_mode
        self.active_region_index = None
        for mode, model in self.models.items():
            inputs = self._input_values(mode)
            if inputs:
                model.set_inputs(inputs, t0)
            model.initialize(t0)
        if self._switch_regions is not None:
            self._copy_outputs(t0)
            region = self._switch_regions.initial_region(float(self._switch_regions.key(self)))
            mode = self._switch_regions.modes[region]
            if mode != self._active_mode:
                self._transfer(mode, t0)
            self._active_mode = mode
            self.active_region_index = region

    def _input_values(self, mode: str | None = None) -> dict[str, Any]:
        """The wrapper's inputs in the units of model `mode` (the active one by default)."""
        conversions = self._to_model[mode or self._active_mode]
        values = {}
        for name, (scale, offset) in conversions.items():
            raw = self.inputs[name].raw()
            values[name] = scale * raw + offset if isinstance(raw, float) else raw
        return values

    def _do_step_internal(self, t: float, dt: float) -> None:
        model = self.active_comp
        inputs = self._input_values()
        if inputs:
            model.set_inputs(inputs, t)
        model._do_step_internal(t, dt)
        model.t = t + dt
        model._update_output_states(t + dt)

    def _update_output_states(self, t: float | None = None,
                              event_names: list[str] | None = None) -> None:
        self._copy_outputs(t)
        self._set_event_ports(t, event_names)

    def _copy_outputs(self, t: float | None) -> None:
        model = self.active_comp
        for name, (scale, offset) in self._from_model[self._active_mode].items():
            raw = model.outputs[name].raw()
            self.outputs[name].set(scale * raw + offset if isinstance(raw, float) else raw, t)

    def evaluate_outputs(self, inputs: dict[str, Any], t: float | None = None
                         ) -> dict[str, Any]:
        return self.active_comp.evaluate_outputs(inputs, t)

    def get_state(self) -> dict[str, dict[str, Any]]:
        return self.active_comp.get_state()

    def set_state(self, state: dict[str, Any], t: float) -> None:
        self.active_comp.set_state(self._adapt_state(state, self._active_mode), t)

    # ---------------------------------------------------------------- rollback
    def can_rollback(self) -> bool:
        modes = self._switch_regions.modes if self._switch_regions else self.models
        return all(self.models[m].can_rollback() for m in modes)

    def snapshot_state(self) -> Any:
        model = self.active_comp
        return (self._active_mode, self.active_region_index, model.snapshot_state(),
                {n: p.raw() for n, p in model.outputs.items()}, model.t)

    def restore_state(self, snapshot: Any, t: float) -> None:
        mode, region, state, outputs, model_t = snapshot
        self._active_mode, self.active_region_index = mode, region
        model = self.active_comp
        for name, value in outputs.items():
            model.outputs[name]._raw = value  # a Python model's ports (an FMU's read the FMU)
        model.restore_state(state, t)
        model.t = model_t

    def _checkpoint_metadata(self) -> Any:
        return {"mode": self._active_mode, "region": self.active_region_index,
                "switches": list(self._switch_events)}

    def _restore_checkpoint_metadata(self, metadata: Any) -> None:
        self._active_mode = metadata["mode"]
        self.active_region_index = metadata["region"]
        self._switch_events = list(metadata["switches"])

    # ---------------------------------------------------------------- switching
    def _handle_events_internal(self, event_names: list[str], t: float) -> None:
        """The active model's events first (its handlers and the wrapper's), then at most one
        region switch, so the incoming model receives the post-event state."""
        model_events = [e for e in event_names if e not in self._boundaries]
        if model_events:
            super()._handle_events_internal(model_events, t)
            model = self.active_comp
            model._event_routes = self._event_routes
            model._handle_events_internal(model_events, t)
        crossed = [e for e in event_names if e in self._boundaries]
        if len(crossed) > 1:
            raise ConfigurationError(f"{self.name}: boundaries {crossed} crossed at one instant "
                                     f"t={t}; the bands must separate them")
        if crossed:
            region = self.active_region_index
            assert self._switch_regions is not None and region is not None
            target = self._boundaries[crossed[0]].target_region(region)
            self._switch(self._switch_regions.modes[target], t)
            self.active_region_index = target

    def _switch_mode(self, new_mode: str, t: float) -> None:
        """Switch to `new_mode` at t with state transfer (switching without regions)."""
        if self._switch_regions is not None:
            raise ConfigurationError(f"{self.name}: with switch regions, the regions choose "
                                     "the model")
        if new_mode not in self.models:
            raise ConfigurationError(f"{self.name}: unknown mode {new_mode!r}; models: "
                                     f"{list(self.models)}")
        self._switch(new_mode, t)

    def _switch(self, new_mode: str, t: float) -> None:
        from_mode = self._active_mode
        source, target, report = self._transfer(new_mode, t)
        self._active_mode = new_mode
        self._switch_events.append(ModeSwitchEvent(
            t, from_mode, new_mode, source if self.record_switch_state else None,
            target if self.record_switch_state else None, report))
        self._copy_outputs(t)
        logger.info("[%s] switching %s -> %s at t=%.8f", self.name, from_mode, new_mode, t)

    def _transfer(self, new_mode: str, t: float) -> tuple[dict, dict, Any]:
        """Import the active model's state into `new_mode` at t. Nothing is committed here:
        if anything raises, the active model stays the active one."""
        source = self.active_comp.get_state()
        incoming = self.models[new_mode]
        inputs = self._input_values(new_mode)
        if inputs:
            incoming.set_inputs(inputs, t)
        incoming.set_state(self._adapt_state(source, new_mode), t)
        incoming.t = t
        target = incoming.get_state()
        return source, target, self._build_transfer_report(source, target,
                                                           self._active_mode, new_mode, t)

    def reset(self) -> None:
        super().reset()
        for model in self.models.values():
            model.reset()
        self._active_mode = self._initial_mode
        self.active_region_index = None
        self._switch_events = []
