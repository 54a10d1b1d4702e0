"""`import syssimx` loads no heavy optional library; units and graph analysis load theirs on use."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
import syssimx

# pint (its registry alone costs more than the rest of syssimx), networkx, and the libraries only
# results, plots and ensembles need
HEAVY = ("pint", "networkx", "pandas", "matplotlib", "scipy", "xarray", "dask")

# the syssimx this test process imports (the source tree with a build, or the installed package)
PYTHON_DIR = Path(syssimx.__file__).resolve().parents[1]


def loaded_after(code: str) -> list[str]:
    """Which of HEAVY a fresh interpreter has imported after running `code`."""
    probe = (f"{code}\nimport json, sys\n"
             f"print(json.dumps([m for m in {HEAVY!r} if m in sys.modules]))")
    environment = dict(os.environ)
    environment["PYTHONPATH"] = os.pathsep.join(
        [str(PYTHON_DIR), *filter(None, [environment.get("PYTHONPATH")])])
    output = subprocess.run([sys.executable, "-c", probe], env=environment, check=True,
                            capture_output=True, text=True).stdout
    return json.loads(output.splitlines()[-1])


def test_import_syssimx_loads_no_heavy_library():
    assert loaded_after("import syssimx") == []


def test_import_syssimx_loads_none_of_its_parts_until_a_name_is_used():
    code = ("import sys, syssimx\n"
            "assert 'numpy' not in sys.modules and 'syssimx.engine' not in sys.modules\n"
            "assert syssimx.System.__module__ == 'syssimx.system.system'\n"
            "assert 'syssimx.components.multi' not in sys.modules")
    assert loaded_after(code) == []


def test_a_component_used_on_its_own_finds_the_system_it_runs_in():
    code = ("from syssimx.components import FMUComponent\nfrom syssimx import fmus\n"
            "gain = FMUComponent('G', fmus.path('gain'))\ngain.set_inputs({'u': 2.0})\n"
            "gain.initialize(0.0)\ngain.do_step(0.0, 0.1)\n"
            "assert gain.get_outputs()['y'].magnitude == 2.0")
    assert "pint" in loaded_after(code)  # the outputs are quantities


def test_a_unit_conversion_loads_pint_and_no_networkx():
    code = ("import syssimx\nfrom syssimx.units import conversion\n"
            "assert conversion('m', 'cm') == (100.0, 0.0)")
    loaded = loaded_after(code)
    assert "pint" in loaded
    assert "networkx" not in loaded


def test_a_graph_analysis_loads_neither_networkx_nor_pint():
    code = ("import syssimx\nfrom syssimx.graph.analysis import analyze\n"
            "components = {'a': {'y': set()}, 'b': {'y': {'u'}}}\n"
            "assert analyze(components, [('a', 'y', 'b', 'u')]).order == ['b', 'a']")
    assert loaded_after(code) == []


def test_simulating_one_fmu_from_the_command_line_loads_no_heavy_library(tmp_path):
    code = ("from syssimx import fmus\nfrom syssimx.cli import main\n"
            "assert main(['simulate', fmus.path('pendulum_euler'), '--stop-time', '0.1', "
            f"'-o', {str(tmp_path / 'out.csv')!r}]) == 0")
    assert loaded_after(code) == []


def test_a_coupled_system_of_fmus_with_equal_units_loads_no_heavy_library():
    code = ("from syssimx import Connection, FMUComponent, System, fmus\n"
            "system = System('pair')\n"
            "for name in ('a', 'b', 'c'):\n"
            "    system.add_component(FMUComponent(name, fmus.path('gain')))\n"
            "system.add_connection(Connection('a', 'y', 'b', 'u'))\n"
            "system.add_connection(Connection('b', 'y', 'c', 'u'))\n"
            "system.initialize(0.0)\nsystem.run(0.0, 0.1, 0.01)")
    assert loaded_after(code) == []


def test_unit_names_resolve_on_first_use():
    from syssimx import units

    length = units.Quantity(2.0, "m")
    assert units.is_quantity(length)
    assert not units.is_quantity(2.0)
    assert units.quantity(3.0, "kg.m2") == units.ureg.Quantity(3.0, "kg*m**2")
    with pytest.raises(units.DimensionalityError):
        units.conversion("m", "s")
    assert units.magnitude_in(length, "cm") == 200.0
