"""The engine's layer check (tests/c/layout/layers.py, run by `meson test` as 'layers') names
what goes up or sideways, on a small tree of its own."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

LAYOUT = Path(__file__).resolve().parents[1] / "c" / "layout"


def _checker() -> ModuleType:
    spec = importlib.util.spec_from_file_location("engine_layers", LAYOUT / "layers.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def _tree(root: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)
    return root


def test_includes_down_pass_and_up_or_sideways_fail(tmp_path):
    layers = _checker()
    level = layers.read_layers("low\nmiddle side  # two folders on one layer\nhigh\n")
    assert level == {"low": 0, "middle": 1, "side": 1, "high": 2}
    src = _tree(tmp_path, {
        "low/base.h": "",
        "middle/part.h": '#include "base.h"\n',
        "middle/part.c": '#include "part.h"\n#include "top.h"\n',
        "middle/deep/inner.c": '#include "other.h"\n',
        "side/other.h": "",
        "high/top.h": '#include "part.h"\n#include <stdio.h>\n#include "fmi2Functions.h"\n',
    })
    assert layers.violations(src, level) == [
        "middle/deep/inner.c includes other.h: middle -> side (sideways)",
        "middle/part.c includes top.h: middle -> high (up)",
    ]


def test_a_file_outside_the_layers_and_a_header_name_twice_fail(tmp_path):
    layers = _checker()
    src = _tree(tmp_path, {"low/a.h": "", "stray/b.c": "", "stray/a.h": ""})
    assert layers.violations(src, {"low": 0}) == [
        "header name a.h is not unique: low/a.h, stray/a.h",
        "stray/a.h: in no folder of layers.txt",
        "stray/b.c: in no folder of layers.txt",
    ]

