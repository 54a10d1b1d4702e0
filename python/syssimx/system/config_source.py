"""Reading a system description (YAML or JSON) and naming where an entry came from.

YAML mappings keep the line they start on, so an error about an entry can point at it.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import ConfigurationError


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
        return ConfigError(f"{prefix + ': ' if prefix else ''}{entry}: {message}")


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
    try:
        return yaml.load(text, Loader=LineLoader)  # a SafeLoader subclass
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        line = f", line {mark.line + 1}" if mark is not None else ""
        problem = getattr(exc, "problem", None) or str(exc)
        raise ConfigError(f"{path}{line}: not valid YAML: {problem}") from exc
