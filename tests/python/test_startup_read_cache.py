"""read_fmu reads each FMU file once per process, re-reads a changed file, and components share
what it read without changing it."""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

import pytest
from fixture_fmus import fmu_path
from syssimx import FMUComponent, FMUFileError, fmus
from syssimx.fmu import info as model_description
from syssimx.fmu.info import read_fmu


@pytest.fixture
def gain_copy(tmp_path: Path) -> Path:
    """A private copy of the gain FMU, so no other test shares its cache entry."""
    path = tmp_path / "gain.fmu"
    shutil.copyfile(fmus.path("gain"), path)
    return path


@pytest.fixture
def descriptions_read(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The files whose modelDescription.xml was parsed during the test."""
    parsed: list[str] = []
    parse = model_description.read_description

    def counting(stream, where, declared_size=None):
        parsed.append(str(where))
        return parse(stream, where, declared_size)

    monkeypatch.setattr(model_description, "read_description", counting)
    return parsed


def test_components_of_one_file_parse_it_once(gain_copy: Path, descriptions_read: list[str]):
    components = [FMUComponent(f"g{i}", str(gain_copy)) for i in range(3)]
    assert descriptions_read == [str(gain_copy.resolve())]
    assert components[0].info is components[2].info


def test_a_relative_path_shares_the_entry_of_the_absolute_one(
        gain_copy: Path, descriptions_read: list[str], monkeypatch: pytest.MonkeyPatch):
    first = read_fmu(gain_copy)
    monkeypatch.chdir(gain_copy.parent)
    assert read_fmu("gain.fmu") is first
    assert len(descriptions_read) == 1


def test_a_changed_file_is_read_again(gain_copy: Path, descriptions_read: list[str]):
    assert read_fmu(gain_copy).model_identifier == "gain"
    stamp = gain_copy.stat()
    shutil.copyfile(fmu_path("keep_defaults"), gain_copy)
    os.utime(gain_copy, ns=(stamp.st_atime_ns, stamp.st_mtime_ns + 1_000_000_000))
    assert read_fmu(gain_copy).model_identifier == "keep_defaults"
    assert len(descriptions_read) == 2


def test_a_touched_file_of_the_same_size_is_read_again(gain_copy: Path,
                                                        descriptions_read: list[str]):
    first = read_fmu(gain_copy)
    stamp = gain_copy.stat()
    os.utime(gain_copy, ns=(stamp.st_atime_ns, stamp.st_mtime_ns + 1_000_000_000))
    assert read_fmu(gain_copy) is not first
    assert len(descriptions_read) == 2


def test_a_failed_read_is_not_cached(tmp_path: Path, descriptions_read: list[str]):
    path = tmp_path / "late.fmu"
    with pytest.raises(FMUFileError, match=re.escape(str(path))):
        read_fmu(path)
    shutil.copyfile(fmus.path("gain"), path)
    assert read_fmu(path).model_identifier == "gain"


def test_a_component_changes_its_copies_not_the_shared_info(gain_copy: Path):
    first = FMUComponent("first", str(gain_copy))
    first.set_inputs({"u": 4.0})
    first.direct_feedthrough["y"].add("extra")
    first.input_specs.pop("u")
    second = FMUComponent("second", str(gain_copy))
    assert second.info is first.info
    assert second.info.input_starts == {"u": 0.0}
    assert second.info.feedthrough == {"y": {"u"}}
    assert set(second.input_specs) == {"u"}
