"""Which classes a system description may name, and finding one without running the file.

A description is data: importing a module runs its code, and calling a class runs its
constructor. So `class: "module:Class"` is resolved in this order, each step only when the one
before passed:

1. the module is syssimx's own, or one the user allowed (`allowed_modules=` of build_system
   and run_from_config, `--allow-module` of the command line); a package allows its submodules;
2. the module is imported (from sys.path, or as a .py file beside the description);
3. the attribute is a class and a subclass of CoSimComponent;

and only then is it constructed with the description's `args`. A module no one allowed is never
imported, so the file cannot make a process load a library or write a file.
"""

from __future__ import annotations

import importlib
import importlib.util
import sys
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from .config_source import Source, quoted

if TYPE_CHECKING:
    from ..components.base import CoSimComponent

TRUSTED_PACKAGE = "syssimx"


def allowed_modules(names: Iterable[str] | str | None) -> tuple[str, ...]:
    """The user's allowed module names, checked (a dotted Python module name each)."""
    if names is None:
        return ()
    if isinstance(names, str):
        names = [names]
    checked = []
    for name in names:
        if not isinstance(name, str) or not all(part.isidentifier()
                                                for part in name.split(".")):
            raise ValueError(f"allowed module {name!r} is not a module name like 'pkg.models'")
        checked.append(name)
    return tuple(checked)


def add_allow_module_option(parser: Any) -> None:
    """The command line's --allow-module (repeatable) on an argparse parser."""
    parser.add_argument("--allow-module", action="append", default=[], metavar="MODULE",
                        dest="allowed_modules",
                        help="let the system file name classes of this module (and its "
                             "submodules); importing it runs its code (repeatable)")


def is_allowed(module_name: str, allowed: Iterable[str]) -> bool:
    """Whether a description may import `module_name`: syssimx's, or allowed (a package
    allows its submodules)."""
    return any(module_name == trusted or module_name.startswith(trusted + ".")
               for trusted in (TRUSTED_PACKAGE, *allowed))


def resolve_component_class(source: Source, label: str, entry: dict, spec: Any
                            ) -> type[CoSimComponent]:
    """The CoSimComponent subclass "module.path:Class" names, imported only when allowed."""
    from ..components.base import CoSimComponent

    if not isinstance(spec, str) or spec.count(":") != 1 or not all(spec.split(":")):
        raise source.error(label, f"class {quoted(spec)} is not of the form "
                           "'module.path:ClassName'", entry)
    module_name, class_name = spec.split(":")
    if not all(part.isidentifier() for part in module_name.split(".")):
        raise source.error(label, f"class {quoted(spec)}: {quoted(module_name)} is not a "
                           "module name", entry)
    if not is_allowed(module_name, source.allowed_modules):
        raise source.error(label, f"module {module_name!r} is not allowed: a system file may "
                           f"name classes of syssimx and of modules you allow (importing a "
                           f"module runs its code); allow it with --allow-module {module_name} "
                           f"or allowed_modules=[{module_name!r}]", entry)
    try:
        module = importlib.import_module(module_name)
    except ModuleNotFoundError as exc:
        module = _module_beside(source, module_name)
        if module is None:
            raise source.error(label, f"cannot import module {module_name!r}: {exc}",
                               entry) from exc
    except ImportError as exc:
        raise source.error(label, f"cannot import module {module_name!r}: {exc}",
                           entry) from exc
    cls = getattr(module, class_name, None)
    if cls is None:
        raise source.error(label, f"module {module_name!r} has no {class_name!r}", entry)
    if not isinstance(cls, type) or not issubclass(cls, CoSimComponent):
        raise source.error(label, f"{spec} is not a CoSimComponent", entry)
    return cls


def _module_beside(source: Source, module_name: str) -> Any:
    """The module `a.b` from <description folder>/a/b.py, or None."""
    path = source.directory.joinpath(*module_name.split(".")).with_suffix(".py")
    if source.path is None or not path.is_file():
        return None
    if module_name in sys.modules:
        return sys.modules[module_name]
    spec = importlib.util.spec_from_file_location(module_name, path)
    if spec is None or spec.loader is None:
        return None
    module = importlib.util.module_from_spec(spec)
    sys.modules[module_name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[module_name]
        raise
    return module
