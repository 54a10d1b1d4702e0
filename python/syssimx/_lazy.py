"""Packages whose public names are imported on first use (a module `__getattr__`, PEP 562):
importing the package loads none of its parts, and a program pays only for those it touches."""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping


def lazy_names(package: str, modules: Mapping[str, str]
               ) -> tuple[Callable[[str], object], Callable[[], list[str]]]:
    """The `__getattr__` and `__dir__` of `package`: each name of `modules` is taken from its
    module (relative to the package) on first access and kept in the package; a name that is
    its module's last part is that module."""

    def attribute(name: str) -> object:
        where = modules.get(name)
        if where is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        module = importlib.import_module(where, package)
        value = module if where.rsplit(".", 1)[-1] == name else getattr(module, name)
        setattr(importlib.import_module(package), name, value)
        return value

    def names() -> list[str]:
        return sorted({*vars(importlib.import_module(package)), *modules})

    return attribute, names
