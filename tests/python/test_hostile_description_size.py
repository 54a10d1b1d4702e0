"""A modelDescription.xml that inflates beyond DESCRIPTION_SIZE_LIMIT is refused before it is
read (its declared size) or while it is (a stream that gives more than its header said): an
FMUFileError naming the file and the limit. Before: a 1 MB FMU whose description inflated to
1 GiB was read whole (1.06 GB peak RSS), its ISO-8859-1 twin ended in a bare MemoryError."""

from __future__ import annotations

import io
import zipfile
from pathlib import Path

import pytest
from syssimx import FMUComponent, fmus
from syssimx.errors import FMUFileError
from syssimx.fmu import description as description_module
from syssimx.fmu.description import read_description

LIMIT = 2**20  # the tests' limit: the gain FMU's description is about 5 kB


@pytest.fixture
def small_limit(monkeypatch: pytest.MonkeyPatch) -> int:
    monkeypatch.setattr(description_module, "DESCRIPTION_SIZE_LIMIT", LIMIT)
    return LIMIT


def padded_gain(tmp_path: Path, encoding: str) -> Path:
    """The gain FMU whose description, declared in `encoding`, is padded with whitespace
    after its root element (well-formed XML) to twice the limit."""
    target = tmp_path / f"padded_{encoding}.fmu"
    with zipfile.ZipFile(fmus.path("gain")) as original, \
            zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as copy:
        for item in original.infolist():
            data = original.read(item)
            if item.filename == "modelDescription.xml":
                data = data.replace(b'encoding="UTF-8"', f'encoding="{encoding}"'.encode())
                data += b" " * (2 * LIMIT)
            copy.writestr(item.filename, data)
    return target


@pytest.mark.parametrize("encoding", ["UTF-8", "ISO-8859-1"])
def test_a_description_declared_larger_than_the_limit_is_refused(tmp_path: Path,
                                                                 small_limit: int,
                                                                 encoding: str):
    path = padded_gain(tmp_path, encoding)
    with pytest.raises(FMUFileError) as caught:
        FMUComponent("G", str(path))
    message = str(caught.value)
    assert message.startswith(f"{path}: modelDescription.xml declares ")
    assert f"more than the {small_limit} bytes syssimx reads of a description" in message


def test_a_stream_longer_than_its_declared_size_stops_at_the_limit(small_limit: int):
    """A header that understates the member: the reading stops one byte past the limit."""
    stream = io.BytesIO(b"<a/>" + b" " * (3 * small_limit))
    with pytest.raises(FMUFileError) as caught:
        read_description(stream, "lying.fmu", 100)
    assert str(caught.value) == (
        f"lying.fmu: modelDescription.xml inflates to more than the {small_limit} bytes "
        "syssimx reads of a description (its archive declares 100)")
    assert stream.tell() == small_limit + 1


def test_a_description_at_the_limit_loads(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    path = padded_gain(tmp_path, "UTF-8")
    with zipfile.ZipFile(path) as archive:
        size = archive.getinfo("modelDescription.xml").file_size
    monkeypatch.setattr(description_module, "DESCRIPTION_SIZE_LIMIT", size)
    assert "u" in FMUComponent("G", str(path)).input_specs


def test_syssimx_info_refuses_it_before_fmpy_reads_it(tmp_path: Path, small_limit: int,
                                                     capsys: pytest.CaptureFixture[str]):
    """Before: FMPy read the whole description (and lxml refused a text node over 10 MB)."""
    from syssimx.cli import main

    path = padded_gain(tmp_path, "UTF-8")
    assert main(["info", str(path)]) == 1
    error = capsys.readouterr().err
    assert error.startswith(f"syssimx: error: {path} is not a readable FMU: {path}: "
                            "modelDescription.xml declares ")
    assert f"more than the {small_limit} bytes syssimx reads of a description" in error
