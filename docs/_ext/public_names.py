"""Links a type to its API page when it is named by the module that defines it.

Signatures and annotations name a class by where it is defined (`syssimx.system.results.
SimulationResult`), but the API reference documents it once, under the path users import it
from (`syssimx.SimulationResult`). On a reference Sphinx cannot resolve, this looks the object
up and, if it is documented under another name, links there instead."""

from __future__ import annotations

import importlib
from typing import Any

from docutils import nodes
from sphinx.addnodes import pending_xref
from sphinx.application import Sphinx
from sphinx.environment import BuildEnvironment


def _object(path: str) -> Any:
    """The object a dotted path names (a module, then attributes), or None."""
    parts = path.split(".")
    for split in range(len(parts), 0, -1):
        try:
            value = importlib.import_module(".".join(parts[:split]))
        except ImportError:
            continue
        try:
            for name in parts[split:]:
                value = getattr(value, name)
        except AttributeError:
            return None
        return value
    return None


def _documented(env: BuildEnvironment) -> dict[int, str]:
    """id(object) -> the name it is documented under, for every documented Python object."""
    names: dict[int, str] = {}
    for name, entry in env.get_domain("py").objects.items():
        if entry.objtype in ("class", "exception", "function", "data", "module") \
                and not entry.aliased:
            value = _object(name)
            if value is not None:
                names.setdefault(id(value), name)
    return names


def resolve(app: Sphinx, env: BuildEnvironment, node: pending_xref,
            contnode: nodes.Element) -> nodes.Element | None:
    if node.get("refdomain") != "py" or not node["reftarget"].startswith("syssimx."):
        return None
    value = _object(node["reftarget"])
    if value is None:
        return None
    public = _documented(env).get(id(value))
    if public is None or public == node["reftarget"]:
        return None
    return env.get_domain("py").resolve_xref(env, node["refdoc"], app.builder,
                                             node["reftype"], public, node, contnode)


def setup(app: Sphinx) -> dict[str, Any]:
    app.connect("missing-reference", resolve)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
