"""Results outlive their System, plot, describe and draw the system."""

from __future__ import annotations

import gc
import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest
from syssimx import FMUComponent, System, fmus

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "hybrid_pendulum.py"


def run_and_forget_the_system() -> object:
    pendulum = FMUComponent("P", fmus.path("pendulum_euler"))
    pendulum.set_parameters(theta0=0.5)
    system = System("short-lived")
    system.add_component(pendulum)
    system.initialize(0.0)
    return system.run(0.0, 0.5, 0.1)


def test_result_stays_valid_after_the_system_is_gone():
    result = run_and_forget_the_system()
    gc.collect()
    t, data = result["P"]
    np.testing.assert_allclose(t, [0.0, 0.1, 0.2, 0.3, 0.4, 0.5], atol=1e-12)
    assert data["theta"][0] == 0.5
    assert np.all(np.diff(data["theta"]) < 0)  # released from rest, it swings down


def test_unknown_component_in_a_result_names_the_known_ones():
    result = run_and_forget_the_system()
    with pytest.raises(KeyError, match=r"'Q'.*\['P'\]"):
        result["Q"]


def test_plot_writes_a_png(tmp_path: Path):
    result = run_and_forget_the_system()
    path = tmp_path / "theta.png"
    result.plot(["P.theta", "P.omega"], path=path)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def load_example():
    spec = importlib.util.spec_from_file_location("hybrid_pendulum", EXAMPLE)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def test_seed_system_describes_and_draws_itself():
    example = load_example()
    system, pendulum = example.build("euler")
    report = system.describe()
    assert pendulum.name in report and "wall_hit" in report
    source = example.picture(system)
    assert "wall_hit" in source and "omega_invert" in source
