"""The API reference covers every public name: each name of `__all__` of syssimx and of its
public subpackages (and the public functions and classes of the modules without `__all__`) is
the object of an entry of docs/api/index.rst, under that name or another public one. The
dataclass options show the engine's defaults in their signatures, not `<factory>`."""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import re
from pathlib import Path

import pytest
import syssimx
from syssimx import GaussSeidelAlgorithm, HybridAlgorithm, JacobiAlgorithm
from syssimx.ensemble import monte_carlo, sweep

API_INDEX = Path(__file__).resolve().parents[2] / "docs" / "api" / "index.rst"

# the packages and modules whose names are public; the version attributes are described in the
# reference's text (they are strings, not objects with a page)
PUBLIC = ["syssimx", "syssimx.algorithms", "syssimx.components", "syssimx.core",
          "syssimx.system", "syssimx.ensemble", "syssimx.ssp", "syssimx.osp", "syssimx.graph",
          "syssimx.fmu", "syssimx.fmus", "syssimx.errors", "syssimx.viz.plot", "syssimx.cli"]
DESCRIBED_IN_TEXT = {"__version__", "__version_info__"}


def public_names(module_name: str) -> list[str]:
    module = importlib.import_module(module_name)
    if hasattr(module, "__all__"):
        return [name for name in module.__all__ if name not in DESCRIBED_IN_TEXT]
    return [name for name, value in vars(module).items()
            if not name.startswith("_") and (inspect.isfunction(value) or inspect.isclass(value))
            and value.__module__ == module_name]


def documented() -> dict[int, str]:
    """id(object) -> its entry in the API reference: autosummary items under their
    currentmodule, auto* and py:data/py:module directives. A module's page documents its
    members, so a documented module's public names count as documented."""
    entries: dict[int, str] = {}
    module = "syssimx"
    in_autosummary = False

    def add(path: str, value: object) -> None:
        entries[id(value)] = path
        if inspect.ismodule(value):
            for name in public_names(value.__name__):
                entries.setdefault(id(getattr(value, name)), f"{path}.{name}")

    for line in API_INDEX.read_text().splitlines():
        if match := re.match(r"\.\. currentmodule:: (\S+)", line):
            module = match.group(1)
        elif line.startswith(".. autosummary::"):
            in_autosummary = True
        elif match := re.match(r"\.\. py:module:: (\S+)", line):
            add(match.group(1), importlib.import_module(match.group(1)))
        elif match := re.match(r"\.\. (?:py:data|autofunction|autoclass):: (\S+)", line):
            # an attribute of its module (a name that is also a submodule's is the attribute)
            owner, name = match.group(1).rsplit(".", 1)
            entries[id(getattr(importlib.import_module(owner), name))] = match.group(1)
        elif in_autosummary and (match := re.match(r"   ([A-Za-z_][\w.]*)$", line)):
            add(f"{module}.{match.group(1)}", resolve(f"{module}.{match.group(1)}"))
        elif in_autosummary and line and not line.startswith(" "):
            in_autosummary = False
    return entries


def resolve(path: str) -> object:
    """What autosummary documents under `path`: the module if one has that name, else the
    attribute."""
    try:
        return importlib.import_module(path)
    except ImportError:
        owner, name = path.rsplit(".", 1)
        return getattr(resolve(owner), name)


def test_the_reference_lists_entries_that_exist():
    assert len(documented()) > 60


@pytest.mark.parametrize("module_name", PUBLIC)
def test_every_public_name_has_an_api_page(module_name: str):
    entries = documented()
    module = importlib.import_module(module_name)
    missing = [name for name in public_names(module_name)
               if id(getattr(module, name)) not in entries]
    assert not missing, f"docs/api/index.rst has no entry for {module_name}: {missing}"


def test_the_top_level_names_are_the_packages_whole_api():
    assert set(public_names("syssimx")) == set(syssimx.__all__) - DESCRIBED_IN_TEXT


@pytest.mark.parametrize("options", [HybridAlgorithm, JacobiAlgorithm, GaussSeidelAlgorithm])
def test_signatures_show_the_engines_defaults(options: type):
    signature = inspect.signature(options)
    assert "<factory>" not in str(signature)
    made = options()
    for field in dataclasses.fields(options):
        if field.init and field.name in signature.parameters:
            assert signature.parameters[field.name].default == getattr(made, field.name), \
                field.name


def _documented_parameters(function: object) -> set[str]:
    """The parameters napoleon renders as fields (":param name:") from the docstring."""
    from sphinx.ext.napoleon import Config
    from sphinx.ext.napoleon.docstring import GoogleDocstring

    rendered = str(GoogleDocstring(inspect.getdoc(function) or "", Config()))
    return set(re.findall(r"^:param (\w+):", rendered, re.M))


@pytest.mark.parametrize("function", [
    syssimx.System.run, syssimx.System.initialize, syssimx.FMUComponent.__init__,
    syssimx.components.CoSimComponent.add_event_indicator, sweep],
    ids=lambda function: function.__qualname__)
def test_the_parameters_are_a_list_of_fields(function) -> None:
    parameters = set(inspect.signature(function).parameters) - {"self"}
    assert _documented_parameters(function) == parameters


def test_monte_carlo_lists_its_own_parameters_and_refers_to_sweep_for_the_rest() -> None:
    assert _documented_parameters(monte_carlo) == {"system", "distributions", "samples", "seed"}
    assert "The other arguments are sweep's." in (monte_carlo.__doc__ or "")
