"""A system description is data: it names classes of syssimx or of modules the user allowed,
never imports anything else and never calls what is not a CoSimComponent; its size once YAML's
aliases are expanded and its nesting are bounded; messages quote only a bounded part of it."""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import pytest
from syssimx.cli import main
from syssimx.system.config_source import MAX_DEPTH, MAX_NODES
from syssimx.system.loader import ConfigError, build_system, load_config, run_from_config

VICTIM_TEXT = "precious data\n"


def victim_and_system(tmp_path: Path, spec: str, args: str) -> tuple[Path, Path]:
    """A file a hostile description's `name` points at, and that description."""
    victim = tmp_path / "victim.txt"
    victim.write_text(VICTIM_TEXT)
    system = tmp_path / "system.yaml"
    system.write_text(f"components:\n  - name: {json.dumps(str(victim))}\n"
                      f"    class: '{spec}'\n    args: {args}\nrun: {{t0: 0, tf: 1, dt: 0.5}}\n")
    return victim, system


@pytest.mark.parametrize(("spec", "args"), [("tarfile:TarFile", "{mode: w}"),
                                             ("ctypes:CDLL", "{}"),
                                             ("os:system", "{}")])
def test_a_module_nobody_allowed_is_not_imported(tmp_path: Path, spec: str, args: str):
    module = spec.split(":")[0]
    victim, system = victim_and_system(tmp_path, spec, args)
    was_imported = module in sys.modules
    with pytest.raises(ConfigError) as caught:
        build_system(system)
    assert str(caught.value).startswith(f"{system}, line 2: components[0] ")
    assert f"module '{module}' is not allowed" in str(caught.value)
    assert f"--allow-module {module}" in str(caught.value)
    assert victim.read_text() == VICTIM_TEXT
    assert (module in sys.modules) == was_imported


def test_an_allowed_module_s_class_is_checked_before_it_is_called(tmp_path: Path):
    """tarfile allowed: TarFile is still not a CoSimComponent, and it is never constructed
    (constructing it with mode 'w' would truncate the victim)."""
    victim, system = victim_and_system(tmp_path, "tarfile:TarFile", "{mode: w}")
    with pytest.raises(ConfigError, match="tarfile:TarFile is not a CoSimComponent"):
        build_system(system, allowed_modules=["tarfile"])
    assert victim.read_text() == VICTIM_TEXT


def test_describe_and_run_refuse_and_name_the_option(tmp_path: Path,
                                                     capsys: pytest.CaptureFixture[str]):
    victim, system = victim_and_system(tmp_path, "tarfile:TarFile", "{mode: w}")
    for command in ("describe", "run"):
        assert main([command, str(system)]) != 0
        error = capsys.readouterr().err
        assert "module 'tarfile' is not allowed" in error and "--allow-module" in error
    assert main(["describe", str(system), "--allow-module", "tarfile"]) != 0
    assert "is not a CoSimComponent" in capsys.readouterr().err
    assert victim.read_text() == VICTIM_TEXT


def test_a_package_allows_its_submodules_only(tmp_path: Path):
    system = tmp_path / "system.yaml"
    system.write_text("components:\n  - {name: A, class: 'quickstart_evil:Thing'}\n")
    with pytest.raises(ConfigError, match="module 'quickstart_evil' is not allowed"):
        build_system(system, allowed_modules=["quickstart"])
    with pytest.raises(ConfigError, match="is not a module name"):
        build_system(system, allowed_modules=["not a module"])


def test_an_allowed_module_that_is_missing_is_named(tmp_path: Path):
    system = tmp_path / "system.yaml"
    system.write_text("components:\n  - {name: A, class: 'no_such_module_here:Thing'}\n")
    with pytest.raises(ConfigError) as caught:
        build_system(system, allowed_modules=["no_such_module_here"])
    assert str(caught.value) == (f"{system}, line 2: components[0] 'A': cannot import module "
                                 "'no_such_module_here': No module named 'no_such_module_here'")


def test_syssimx_classes_need_no_permission():
    system = build_system({"components": [{"name": "P", "class": "syssimx:FMUComponent",
                                           "args": {"fmu_path": "pendulum_euler"}}]})
    assert "P" in system.components


def alias_bomb(levels: int) -> str:
    """Each level's list holds the previous one ten times: 10**levels leaves, a few hundred
    bytes of text."""
    lines = ["a0: &a0 [x, x, x, x, x, x, x, x, x, x]"]
    for k in range(1, levels):
        lines.append(f"a{k}: &a{k} [" + ", ".join([f"*a{k - 1}"] * 10) + "]")
    return "\n".join(lines) + "\ncomponents:\n  - name: B\n    class: 'syssimx:FMUComponent'\n" \
        f"    args: {{fmu_path: pendulum_euler, boom: *a{levels - 1}}}\n"


def test_an_alias_bomb_is_refused_before_it_is_built(tmp_path: Path):
    path = tmp_path / "bomb.yaml"
    path.write_text(alias_bomb(9))  # 10**9 values
    assert path.stat().st_size < 1024
    started = time.process_time()
    with pytest.raises(ConfigError) as caught:
        build_system(path)
    assert str(caught.value) == (f"{path}: expands to more than {MAX_NODES} values (aliases "
                                 "counted where they are used)")
    assert time.process_time() - started < 5  # before: minutes, then MemoryError


def test_aliases_below_the_limit_are_read(tmp_path: Path):
    path = tmp_path / "aliases.yaml"
    path.write_text(alias_bomb(3))  # 1 000 values
    assert len(load_config(path)["a2"]) == 10


def test_an_alias_inside_its_own_anchor_is_refused(tmp_path: Path):
    path = tmp_path / "loop.yaml"
    path.write_text("components: &c [*c]\n")
    with pytest.raises(ConfigError, match=r"loop\.yaml, line 1: an alias refers to the "
                       "collection that contains it"):
        load_config(path)


@pytest.mark.parametrize(("name", "text"), [
    ("deep.yaml", "components: " + "[" * 50_000 + "]" * 50_000 + "\n"),
    ("deep.json", '{"components": ' + "[" * 50_000 + "]" * 50_000 + "}"),
    ("moderate.yaml", "components: " + "[" * (MAX_DEPTH + 5) + "]" * (MAX_DEPTH + 5) + "\n"),
    ("moderate.json", '{"components": ' + "[" * (MAX_DEPTH + 5) + "]" * (MAX_DEPTH + 5) + "}"),
])
def test_deep_nesting_is_a_config_error_naming_the_file(tmp_path: Path, name: str, text: str):
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(ConfigError, match=rf"{name}.*nested deeper than {MAX_DEPTH} levels"):
        run_from_config(path)


def test_the_command_line_names_the_file_of_a_deep_description(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    path = tmp_path / "deep.yaml"
    path.write_text("components: " + "[" * 50_000 + "]" * 50_000 + "\n")
    assert main(["describe", str(path)]) != 0
    error = capsys.readouterr().err
    assert str(path) in error and "RecursionError" not in error


def test_messages_quote_a_bounded_part_of_a_value(tmp_path: Path):
    path = tmp_path / "long.yaml"
    path.write_text("components:\n  - name: A\n    class: 'syssimx:FMUComponent'\n"
                    f"    args: {{fmu_path: pendulum_euler, junk: '{'x' * 1_000_000}'}}\n")
    with pytest.raises(ConfigError) as caught:
        build_system(path)
    assert "cannot construct syssimx:FMUComponent" in str(caught.value)
    assert len(str(caught.value)) < 2000


def test_an_ssp_entity_in_element_content_is_an_ssp_error(tmp_path: Path):
    """Before: lxml's XMLSchemaValidateError ("Internal error in XML Schema validation")."""
    from syssimx.ssp import SSPError, read

    secret = tmp_path / "secret.txt"
    secret.write_text("not for a system file\n")
    path = tmp_path / "SystemStructure.ssd"
    path.write_text(
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<!DOCTYPE ssd:SystemStructureDescription [<!ENTITY e SYSTEM "{secret.as_uri()}">]>\n'
        '<ssd:SystemStructureDescription '
        'xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription" '
        'xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon" version="1.0" '
        'name="x"><ssd:System name="root"><ssd:Annotations><ssc:Annotation type="x">&e;'
        '</ssc:Annotation></ssd:Annotations></ssd:System></ssd:SystemStructureDescription>\n')
    with pytest.raises(SSPError) as caught:
        read(path)
    assert str(path) in str(caught.value) or path.name in str(caught.value)
    assert "cannot be checked against the SSP 1.0 schema" in str(caught.value)
    assert "not for a system file" not in str(caught.value)
