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
    imports = _imports(PACKAGE / "system" / "system.py")
    assert {"syssimx.bridge.plan", "syssimx.components.base",
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


# The package's rooms from the ground up: a room imports only rooms on a lower floor (or its
# own). The CLI and the package's face stand above everything.
FLOORS = (
    ("_paths", "_lazy", "_version", "errors", "atomic_file", "streaming"),
    ("engine", "units", "extras", "partial_results"),
    ("core",),
    ("plan",),
    ("bridge", "fmus", "graph"),
    ("viz", "fmu"),
    ("components",),
    ("export", "ssp_format"),
    ("system",),
    ("ssp", "ensemble", "algorithms"),
    ("osp", "output_check"),
    ("system_files",),
    ("cli",),
)

# No import runs down from a higher floor. System.to_ssp, the one that did, imports the SSP
# writer from ssp_format, which knows no System (it reads the one it is handed) and stands
# below system, as the FMU exporter does; the ssp package, which builds Systems from SSP files,
# stands above. Any upward import fails test_rooms_import_only_rooms_below_them.
UPWARD: frozenset[tuple[str, str]] = frozenset()


def _room(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[0] == "syssimx" else None


def _room_imports() -> set[tuple[str, str]]:
    """(room, room it imports) over every module of the package but its face (__init__)."""
    found = set()
    for path in PACKAGE.rglob("*.py"):
        room = _room(_module_name(path))
        if room is None:
            continue
        for target in _imports(path):
            other = _room(target)
            if other is not None and other != room:
                found.add((room, other))
    return found


def test_every_room_stands_on_a_floor():
    rooms = {_room(_module_name(p)) for p in PACKAGE.rglob("*.py")} - {None}
    placed = {room for floor in FLOORS for room in floor}
    assert rooms - placed == set(), "a new room: put it on a floor of FLOORS"


def test_rooms_import_only_rooms_below_them():
    floor = {room: level for level, rooms in enumerate(FLOORS) for room in rooms}
    upward = {(room, other) for room, other in _room_imports()
              if other in floor and floor[other] >= floor[room]}
    assert upward == UPWARD


def test_no_module_needs_a_module_that_needs_it_back():
    """A module imports only modules that do not import it back, however far round
    (typing-only imports count: a Protocol names what a module reads instead). The packages'
    faces (__init__.py) are left out: they only hand on names, and `from .. import units`
    names the face as well as the module."""
    imports = {_module_name(path): _imports(path) for path in PACKAGE.rglob("*.py")
               if path.name != "__init__.py"}
    graph = {module: {t for t in targets if t in imports} for module, targets in imports.items()}

    def reaches(start: str, goal: str) -> bool:
        seen, todo = set(), [start]
        while todo:
            module = todo.pop()
            for nxt in graph[module]:
                if nxt == goal:
                    return True
                if nxt not in seen:
                    seen.add(nxt)
                    todo.append(nxt)
        return False

    circles = sorted(f"{m} <-> {t}" for m, targets in graph.items() for t in targets
                     if t != m and reaches(t, m))
    assert circles == []
