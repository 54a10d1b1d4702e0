"""Reading a system description (YAML or JSON) and naming where an entry came from.

YAML mappings keep the line they start on, so an error about an entry can point at it.
A file is bounded before it is built into Python objects: at most MAX_NODES values once YAML's
aliases are expanded (a kilobyte of nested aliases can stand for billions) and at most
MAX_DEPTH levels of nesting; messages quote a value at most QUOTED characters long.
"""

from __future__ import annotations

import json
import reprlib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import ConfigurationError

MAX_NODES = 200_000  # values in a description, aliases expanded: far beyond any real system
MAX_DEPTH = 100  # levels of nesting: a system description has fewer than ten
QUOTED = 200  # characters of a value a message quotes


class ConfigError(ConfigurationError):
    """A system description is invalid. The message names the file, the entry and what is
    wrong (and the entry's YAML line when the file is YAML)."""


class LocatedDict(dict):
    """A mapping read from YAML, with the 1-based line it starts on."""

    line: int | None = None


@dataclass(frozen=True)
class Source:
    """Where a description came from: its file (None for a mapping given in Python)."""

    path: Path | None = None
    allowed_modules: tuple[str, ...] = ()  # besides syssimx, where `class:` may come from

    @property
    def directory(self) -> Path:
        """Relative module and FMU paths are looked up here."""
        return self.path.parent if self.path is not None else Path.cwd()

    def error(self, entry: str, message: str, node: object = None) -> ConfigError:
        """ConfigError "<file>, line <n>: <entry>: <message>"."""
        where = [str(self.path)] if self.path is not None else []
        line = getattr(node, "line", None)
        if line is not None:
            where.append(f"line {line}")
        prefix = ", ".join(where)
        return ConfigError(f"{prefix + ': ' if prefix else ''}{_cut(entry)}: {_cut(message)}")


def quoted(value: object) -> str:
    """repr(value), at most about QUOTED characters: a message never grows with the file."""
    shortener = reprlib.Repr()
    shortener.maxstring = shortener.maxother = QUOTED // 2
    shortener.maxlevel, shortener.maxdict, shortener.maxlist = 3, 8, 8
    return _cut(shortener.repr(value))


def _cut(text: str) -> str:
    return text if len(text) <= 4 * QUOTED else text[:4 * QUOTED] + "..."


def kind(value: object) -> str:
    """How a description names a value's type: mapping, list, string, number, ..."""
    if isinstance(value, dict):
        return "mapping"
    return {list: "list", str: "string", int: "number", float: "number", bool: "boolean",
            type(None): "nothing"}.get(type(value), type(value).__name__)


def read_file(path: str | Path) -> dict[str, Any]:
    """The description in a .json file (JSON) or any other file (YAML), as a mapping."""
    source = Source(Path(path))
    try:
        text = source.path.read_text(encoding="utf-8")  # type: ignore[union-attr]
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f"{path}: cannot read the system description: {exc}") from exc
    if source.path.suffix.lower() == ".json":  # type: ignore[union-attr]
        try:
            config = json.loads(text)
        except json.JSONDecodeError as exc:
            raise ConfigError(f"{path}, line {exc.lineno}: not valid JSON: {exc.msg}") from exc
        except RecursionError as exc:
            raise ConfigError(f"{path}: nested deeper than {MAX_DEPTH} levels") from exc
        _check_json_shape(path, config)
    else:
        config = _read_yaml(path, text)
    if not isinstance(config, dict):
        raise ConfigError(f"{path}: the top level of a system description must be a mapping "
                          f"(system, components, connections, ...), got "
                          f"{kind(config)}")
    return config


def _read_yaml(path: str | Path, text: str) -> Any:
    import yaml

    class LineLoader(yaml.SafeLoader):
        """SafeLoader whose mappings remember their first line."""

    def mapping(loader: LineLoader, node: yaml.MappingNode) -> Any:
        data = LocatedDict()
        data.line = node.start_mark.line + 1
        yield data
        data.update(loader.construct_mapping(node))

    LineLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, mapping)
    loader = LineLoader(text)  # a SafeLoader subclass
    try:
        node = loader.get_single_node()  # the node graph: an alias is a shared node
        if node is None:
            return None
        _check_yaml_shape(path, node)
        return loader.construct_document(node)
    except RecursionError as exc:
        raise ConfigError(f"{path}: nested deeper than {MAX_DEPTH} levels") from exc
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        line = f", line {mark.line + 1}" if mark is not None else ""
        problem = getattr(exc, "problem", None) or str(exc)
        raise ConfigError(f"{path}{line}: not valid YAML: {_cut(problem)}") from exc
    finally:
        loader.dispose()


def _check_yaml_shape(path: str | Path, root: Any) -> None:
    """Refuses a node graph that expands past MAX_NODES values or MAX_DEPTH levels, or that
    contains itself (an alias inside its own anchor), before anything is constructed. Each
    node's expanded size is computed once, so a bomb costs its size in the file, not more."""
    import yaml

    sizes: dict[int, int] = {}
    on_path: set[int] = set()
    stack: list[tuple[Any, int, bool]] = [(root, 1, False)]
    while stack:
        node, depth, children_done = stack.pop()
        key = id(node)
        if children_done:
            on_path.discard(key)
            sizes[key] = 1 + sum(sizes[id(child)] for child in _children(yaml, node))
            if sizes[key] > MAX_NODES:
                raise ConfigError(f"{path}: expands to more than {MAX_NODES} values (aliases "
                                  "counted where they are used)")
            continue
        if key in sizes:
            continue
        if key in on_path:
            raise ConfigError(f"{path}, line {node.start_mark.line + 1}: an alias refers to "
                              "the collection that contains it")
        if depth > MAX_DEPTH:
            raise ConfigError(f"{path}, line {node.start_mark.line + 1}: nested deeper than "
                              f"{MAX_DEPTH} levels")
        on_path.add(key)
        stack.append((node, depth, True))
        stack.extend((child, depth + 1, False) for child in _children(yaml, node))


def _children(yaml: Any, node: Any) -> list[Any]:
    if isinstance(node, yaml.MappingNode):
        return [part for pair in node.value for part in pair]
    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    return []


def _check_json_shape(path: str | Path, config: Any) -> None:
    """JSON has no aliases: its values are what the text holds; only the nesting is bounded."""
    stack: list[tuple[Any, int]] = [(config, 1)]
    while stack:
        value, depth = stack.pop()
        if depth > MAX_DEPTH:
            raise ConfigError(f"{path}: nested deeper than {MAX_DEPTH} levels")
        if isinstance(value, dict):
            stack.extend((item, depth + 1) for item in value.values())
        elif isinstance(value, list):
            stack.extend((item, depth + 1) for item in value)
