"""The Python layers import one way: system/ builds on components/, both build on bridge/.

Every import of every module counts (also those inside functions or under TYPE_CHECKING)."""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "python" / "syssimx"


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports(path: Path) -> set[str]:
    """The modules `path` imports, as absolute names."""
    name = _module_name(path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = package.split(".")
            if node.level:
                base = base[:len(base) - node.level + 1]
            target = ".".join([*base, node.module] if node.module else base) if node.level \
                else node.module or ""
            found.add(target)
            found.update(f"{target}.{alias.name}" for alias in node.names)
    return found


def _imports_of(room: str) -> dict[str, set[str]]:
    return {_module_name(path): _imports(path) for path in (PACKAGE / room).rglob("*.py")}


def _reaching(imports: dict[str, set[str]], room: str) -> list[str]:
    prefix = f"syssimx.{room}"
    return sorted(f"{module} imports {target}" for module, targets in imports.items()
                  for target in targets if target == prefix or target.startswith(prefix + "."))


def test_relative_imports_resolve_to_module_names():
    imports = _imports(PACKAGE / "system" / "table_starts.py")
    assert {"syssimx.bridge.plan", "syssimx.components.table_source",
            "syssimx.system.connection"} <= imports


def test_components_never_import_system():
    assert _reaching(_imports_of("components"), "system") == []


def test_bridge_imports_neither_components_nor_system():
    bridge = _imports_of("bridge")
    assert _reaching(bridge, "components") + _reaching(bridge, "system") == []


def test_system_builds_on_components_and_bridge():
    system = _imports_of("system")
    assert _reaching(system, "components") and _reaching(system, "bridge")


def test_fmu_files_build_on_neither_components_nor_system():
    """The FMU seam (archive, description, loading, instance) knows no component kind."""
    fmu = _imports_of("fmu")
    assert _reaching(fmu, "components") + _reaching(fmu, "system") == []


def test_components_keep_only_component_kinds():
    """What reads, extracts and loads FMU files lives in syssimx.fmu."""
    kinds = {path.stem for path in (PACKAGE / "components").glob("*.py")}
    assert not kinds & {"archive", "extraction", "model_description", "description_reader",
                        "description_fmi3", "fmu_instance", "variable_table", "fmi3_arrays"}
