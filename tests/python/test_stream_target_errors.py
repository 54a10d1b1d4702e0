"""A stream target that cannot be written is a ConfigurationError naming it, raised before the
run (before: IsADirectoryError, FileNotFoundError, and numpy's ValueError for a NetCDF file
whose columns coincide)."""

from __future__ import annotations

from pathlib import Path

import pytest
from syssimx import CoSimComponent, FMUComponent, PortSpec, PortType, System, fmus
from syssimx.errors import ConfigurationError


class Constant(CoSimComponent):
    """One Real output of a given name, always 1."""

    def __init__(self, name: str, output: str) -> None:
        super().__init__(name)
        self.output_specs[output] = PortSpec(output, PortType.REAL, "out")
        self.output = output

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _update_output_states(self, t: float | None = None, event_names=None) -> None:
        self.outputs[self.output].set(1.0, t)


def gain_system() -> System:
    system = System("s")
    system.add_component(FMUComponent("G", fmus.path("gain")))
    system.initialize(0.0)
    return system


@pytest.mark.parametrize(("target", "reason"), [
    ("out.csv", "Is a directory"),
    ("missing/out.csv", "No such file or directory"),
])
def test_an_unwritable_stream_target_is_a_configuration_error(tmp_path: Path, target: str,
                                                              reason: str):
    (tmp_path / "out.csv").mkdir()
    path = tmp_path / target
    with pytest.raises(ConfigurationError) as caught:
        gain_system().run(0.0, 0.1, 0.01, stream_to=path)
    assert str(caught.value) == f"cannot stream a run to {path}: {reason}"


@pytest.mark.parametrize("suffix", [".nc", ".csv"])
def test_columns_that_coincide_are_refused_naming_them(tmp_path: Path, suffix: str):
    system = System("s")
    system.add_component(Constant("a.b", "c"))
    system.add_component(Constant("a", "b.c"))
    system.initialize(0.0)
    path = tmp_path / f"out{suffix}"
    with pytest.raises(ConfigurationError) as caught:
        system.run(0.0, 0.1, 0.01, stream_to=path)
    assert str(caught.value) == (f"cannot stream a run to {path}: the columns 'a.b.c' would "
                                 "each be written twice (component.output names that "
                                 "coincide); rename a component")
    assert not path.exists()
