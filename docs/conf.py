"""Sphinx configuration of the syssimx documentation (MyST Markdown, notebooks executed by
MyST-NB at every build, the API reference generated from the docstrings)."""

from __future__ import annotations

import sys
from pathlib import Path

import syssimx

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS / "_ext"))

project = "syssimx"
author = "the syssimx developers"
copyright = "2026, the syssimx developers"  # noqa: A001 (Sphinx's name)
release = syssimx.__version__
version = ".".join(release.split(".")[:2])

extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "offline_mathjax",
    "cli_reference",
    "public_names",
]

exclude_patterns = ["_build", "jupyter_execute", "**.ipynb_checkpoints"]
templates_path = ["_templates"]

# Markdown and notebooks: every notebook (a page with a kernelspec) runs at every build, in a
# temporary folder, and an error in any cell fails the build
myst_enable_extensions = ["colon_fence", "deflist", "dollarmath", "amsmath"]
myst_heading_anchors = 3
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_execution_timeout = 600
nb_execution_in_temp = True
nb_merge_streams = True

# API reference: numpy-style docstrings, one page per public name
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_preserve_defaults = False
# numpy style is the norm; older docstrings in Google style ("Args:") render as well
napoleon_google_docstring = True
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_use_ivar = True  # "Attributes:" as fields: dataclass fields have entries of their own

nitpicky = True
# types from outside syssimx that the offline build cannot link (no intersphinx inventories)
nitpick_ignore_regex = [
    ("py:.*", r"(numpy|np|nx|pint|pandas|pd|xarray|xr|dask|distributed|networkx|graphviz|"
              r"matplotlib|scipy|fmpy|cffi|collections|typing|pathlib|os|types|logging|"
              r"argparse|concurrent|enum|dataclasses|io)\..*"),
    ("py:.*", r"(Any|Callable|Iterable|Iterator|Mapping|Sequence|MutableMapping|Path|"
              r"NDArray|ndarray|Quantity|Unit|DataFrame|Dataset|Client|Figure|Axes|Digraph|"
              r"TextIO|Self|Literal|ClassVar|InitVar|Generator|EllipsisType|PathLike|"
              r"Future|LocalCluster|UnitRegistry|ModuleType|Namespace|ArgumentParser|"
              r"optional|default|array_like|callable|file-like)"),
]

# classes public methods return whose names are not exported (reached through the objects)
nitpick_ignore = [
    ("py:class", "ComponentHistory"),
    ("py:class", "syssimx.system.results.HistoryView"),
    # what System.run hands the result it makes (SimulationResult and its from_system)
    ("py:class", "syssimx.system.results.StatisticsReading"),
    ("py:class", "syssimx.system.recorded_events.RecordedEvents"),
    ("py:class", "syssimx.bridge.run_outcome.RunOutcome"),
    # SimulationResult.events: a list of EventRecords with lookups by (component, event)
    ("py:class", "syssimx.system.event_log.EventLog"),
    ("py:class", "syssimx.components.switch_regions.RegionBoundary"),
    ("py:class", "syssimx.components.restart.Term"),
    # the parts of an FMUInfo (syssimx.fmu): the modelDescription as read, its variables
    ("py:class", "ModelDescription"),
    ("py:class", "ScalarVariable"),
    ("py:class", "EngineTable"),
    ("py:class", "Parameter"),
    ("py:class", "FMUInterface"),
    ("py:class", "Standard"),
    ("py:class", "ClockStructure"),
    # what a reader or writer reads of the objects it is given (Protocols of syssimx's rooms)
    ("py:class", "syssimx.system.results.RecordedSystem"),
    ("py:class", "syssimx.ssp_format.writer.WrittenSystem"),
    ("py:class", "syssimx.system.system_history.HistorySource"),
    # OSPImported.power_bonds: the bonds an OSP structure names
    ("py:class", "syssimx.osp.build.PowerBond"),
    # MemberRuns[k]: one member's samples; ScheduledExecutionComponent.ticks: its log
    ("py:class", "syssimx.system.member_runs.MemberSamples"),
    ("py:class", "syssimx.components.scheduled_execution.Tick"),
    # a SystemState is made by System.save_state from the System's engine plan
    ("py:class", "EnginePlan"),
]

html_theme = "sphinx_book_theme"
html_title = f"syssimx {release}"
html_theme_options = {
    "show_toc_level": 2,
    "home_page_in_toc": True,
    "use_download_button": False,
}
# the theme's colour mode before a reader picks one (else its script logs a console error on
# a first visit)
html_context = {"default_mode": "auto"}
html_last_updated_fmt = None
