"""Broken and hostile FMU archives, built here from the bundled gain.fmu: every problem is an
FMUFileError whose message names the file, and no extraction folder is left behind."""

from __future__ import annotations

import re
import shutil
import stat
import subprocess
import sys
import tempfile
import textwrap
import zipfile
from collections.abc import Callable
from pathlib import Path

import pytest
from syssimx import FMUComponent, fmus
from syssimx.errors import ConfigurationError, FMUFileError
from syssimx.fmu.archive import SIZE_LIMIT_VARIABLE

GAIN = Path(fmus.path("gain"))
# the size limit of these tests: the gain FMU's own content (larger in a debug build) and room,
# but less than it with the 300 000 bytes of `oversized`
with zipfile.ZipFile(GAIN) as gain_archive:
    LIMIT = sum(entry.file_size for entry in gain_archive.infolist()) + 100_000
BINARY = "binaries/linux64/gain.so"


def gain_entries() -> dict[str, bytes]:
    with zipfile.ZipFile(GAIN) as archive:
        return {name: archive.read(name) for name in archive.namelist()}


def description() -> str:
    return gain_entries()["modelDescription.xml"].decode()


def write_archive(path: Path, entries: dict[str | zipfile.ZipInfo, bytes]) -> Path:
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in entries.items():
            archive.writestr(name, data)
    return path


def edited(tmp_path: Path, old: str, new: str) -> Path:
    """gain.fmu with one edit of its modelDescription.xml."""
    text = description()
    assert old in text
    entries = {**gain_entries(), "modelDescription.xml": text.replace(old, new, 1).encode()}
    return write_archive(tmp_path / "edited.fmu", entries)


def without_interfaces(tmp_path: Path) -> Path:
    """gain.fmu without its CoSimulation and ModelExchange elements."""
    text = re.sub(r"  <(CoSimulation|ModelExchange) .*?/>\n", "", description(), flags=re.S)
    return write_archive(tmp_path / "edited.fmu",
                         {**gain_entries(), "modelDescription.xml": text.encode()})


def with_entry(tmp_path: Path, entry: str | zipfile.ZipInfo, data: bytes = b"x") -> Path:
    return write_archive(tmp_path / "extra.fmu", {**gain_entries(), entry: data})


def symlink_entry(tmp_path: Path) -> Path:
    link = zipfile.ZipInfo("resources/passwd")
    link.external_attr = (stat.S_IFLNK | 0o777) << 16
    return with_entry(tmp_path, link, b"/etc/passwd")


def corrupt(tmp_path: Path, member: str) -> Path:
    """gain.fmu with bytes in the middle of `member`'s compressed data flipped."""
    path = write_archive(tmp_path / "corrupt.fmu", gain_entries())
    with zipfile.ZipFile(path) as archive:
        info = archive.getinfo(member)
    data = bytearray(path.read_bytes())
    start = info.header_offset + 30 + len(info.filename.encode()) + len(info.extra)
    middle = start + info.compress_size // 2
    data[middle:middle + 8] = bytes(b ^ 0x5A for b in data[middle:middle + 8])
    path.write_bytes(bytes(data))
    return path


def not_a_zip(tmp_path: Path) -> Path:
    path = tmp_path / "text.fmu"
    path.write_text("just text")
    return path


def truncated(tmp_path: Path) -> Path:
    path = tmp_path / "truncated.fmu"
    path.write_bytes(GAIN.read_bytes()[:2000])
    return path


def without(tmp_path: Path, name: str) -> Path:
    entries = gain_entries()
    del entries[name]
    return write_archive(tmp_path / "partial.fmu", entries)


def with_member_header(tmp_path: Path, name: str, flag_bits: int = 0,
                       method: int | None = None) -> Path:
    """gain.fmu, stored, with member `name`'s general purpose flags OR-ed with `flag_bits`
    and its compression method set to `method`, in its local and its central header (as an
    archiver that encrypts, or compresses with Deflate64, writes them)."""
    path = tmp_path / "patched.fmu"
    with zipfile.ZipFile(path, "w", zipfile.ZIP_STORED) as archive:
        for entry, data in gain_entries().items():
            archive.writestr(entry, data)
    raw = bytearray(path.read_bytes())
    with zipfile.ZipFile(path) as archive:
        local = archive.getinfo(name).header_offset
    encoded, central = name.encode(), 0
    while raw[central + 46:central + 46 + len(encoded)] != encoded:
        central = raw.index(b"PK\x01\x02", central + 1)
    for flags_at in (local + 6, central + 8):
        raw[flags_at] |= flag_bits
    if method is not None:
        for method_at in (local + 8, central + 10):
            raw[method_at:method_at + 2] = method.to_bytes(2, "little")
    path.write_bytes(bytes(raw))
    return path


def garbage_binary(tmp_path: Path) -> Path:
    return write_archive(tmp_path / "garbage.fmu", {**gain_entries(), BINARY: b"not ELF"})


def oversized(tmp_path: Path) -> Path:
    return with_entry(tmp_path, "resources/zeros.bin", bytes(300_000))


Build = Callable[[Path], Path]
VARIABLE_U = '<ScalarVariable name="u" valueReference="1"'
# the description names the binary in its ModelExchange element too; syssimx reads CoSimulation's
CO_SIMULATION_ID = '<CoSimulation modelIdentifier="gain"'

# name -> (archive builder, what the message says besides the file)
CASES: dict[str, tuple[Build, str]] = {
    "missing file": (lambda tmp: tmp / "absent.fmu", "FMU file not found"),
    "not a zip": (not_a_zip, "not a readable zip archive"),
    "truncated zip": (truncated, "not a readable zip archive"),
    "no modelDescription": (lambda tmp: without(tmp, "modelDescription.xml"),
                            "no modelDescription.xml"),
    "no binary": (lambda tmp: without(tmp, BINARY), "no linux64 binary"),
    "absolute entry": (lambda tmp: with_entry(tmp, "/tmp/evil.so"), "has an absolute path"),
    "dot-dot entry": (lambda tmp: with_entry(tmp, "resources/../../evil.so"),
                      "climbs out of the archive"),
    "symlink entry": (symlink_entry, "is a symbolic link"),
    "5000-character name": (lambda tmp: with_entry(tmp, "resources/" + "a" * 5000),
                            "longer than 255 bytes"),
    "size over the limit": (oversized, f"inflates to more than {LIMIT} bytes"),
    "corrupt binary": (lambda tmp: corrupt(tmp, BINARY), "corrupt archive member"),
    # before: RuntimeError (password required), "corrupt archive" for Deflate64
    "encrypted modelDescription": (
        lambda tmp: with_member_header(tmp, "modelDescription.xml", flag_bits=1),
        "archive entry 'modelDescription.xml' is encrypted"),
    "encrypted binary": (lambda tmp: with_member_header(tmp, BINARY, flag_bits=1),
                         f"archive entry '{BINARY}' is encrypted"),
    "Deflate64 binary": (lambda tmp: with_member_header(tmp, BINARY, method=9),
                         "is compressed with Deflate64 (method 9), which syssimx cannot "
                         "inflate"),
    "corrupt modelDescription": (lambda tmp: corrupt(tmp, "modelDescription.xml"),
                                 "modelDescription.xml"),
    "binary that is not a library": (garbage_binary, "cannot load binaries/linux64/gain.so"),
    "malformed XML": (lambda tmp: edited(tmp, "</ModelVariables>", "</ModelVariable>"),
                      "not well-formed XML"),
    # FMI 1.0 is read in its own words: FMI 2.0's causality "parameter" is not one of them
    "FMI 1.0": (lambda tmp: edited(tmp, 'fmiVersion="2.0"', 'fmiVersion="1.0"'),
                "variable 'k': causality='parameter' with variability='fixed' is not allowed"),
    "FMI 4.0": (lambda tmp: edited(tmp, 'fmiVersion="2.0"', 'fmiVersion="4.0"'),
                "FMI version 4.0 is not supported (syssimx runs FMI 1.0, FMI 2.0 and FMI 3.0 "
                "Co-Simulation and Model Exchange FMUs)"),
    # FMI 3.0 is read by its own reader, which finds ScalarVariables where it expects <Float64>
    "FMI 3.0": (lambda tmp: edited(tmp, 'fmiVersion="2.0"', 'fmiVersion="3.0"'),
                "modelDescription.xml declares FMI 3.0 but is not a readable FMI 3.0 "
                "description (KeyError: 'ScalarVariable')"),
    "no interface": (without_interfaces, "declares neither CoSimulation nor ModelExchange"),
    "modelIdentifier with ../": (
        lambda tmp: edited(tmp, CO_SIMULATION_ID, '<CoSimulation modelIdentifier="../../evil"'),
        "modelIdentifier '../../evil' is not a file name"),
    "modelIdentifier with /": (
        lambda tmp: edited(tmp, CO_SIMULATION_ID, '<CoSimulation modelIdentifier="/tmp/evil"'),
        "modelIdentifier '/tmp/evil' is not a file name"),
    "no modelIdentifier": (lambda tmp: edited(tmp, CO_SIMULATION_ID, "<CoSimulation"),
                           "no modelIdentifier"),
    "negative value reference": (
        lambda tmp: edited(tmp, VARIABLE_U, '<ScalarVariable name="u" valueReference="-1"'),
        "variable 'u': valueReference -1 is outside 0..4294967295"),
    "value reference of 2**32": (
        lambda tmp: edited(tmp, VARIABLE_U, '<ScalarVariable name="u" valueReference="4294967296"'),
        "variable 'u': valueReference 4294967296 is outside 0..4294967295"),
    "value reference not a number": (
        lambda tmp: edited(tmp, VARIABLE_U, '<ScalarVariable name="u" valueReference="one"'),
        "variable 'u': valueReference 'one' is not an integer"),
    "start not a number": (lambda tmp: edited(tmp, 'start="1"', 'start="one"'),
                           "variable 'k': start 'one' is not a Real value"),
    "undefined declaredType": (lambda tmp: edited(tmp, '<Real start="1"/>',
                                                  '<Real declaredType="Gain" start="1"/>'),
                               "variable 'k': declaredType 'Gain' is not defined"),
    "variable without a type": (lambda tmp: edited(tmp, '<Real start="1"/>', ""),
                                "variable 'k' has no type element"),
    "illegal causality and variability": (
        lambda tmp: edited(tmp, 'causality="input" variability="continuous"',
                           'causality="input" variability="fixed"'),
        "variable 'u': causality='input' with variability='fixed' is not allowed"),
    "ModelStructure index of no variable": (
        lambda tmp: edited(tmp, '<Unknown index="1" dependencies="2"/>',
                           '<Unknown index="9" dependencies="2"/>'),
        "ModelStructure index '9' names no variable"),
    "DefaultExperiment tolerance not a number": (
        lambda tmp: edited(tmp, "<DefaultExperiment ", '<DefaultExperiment tolerance="tight" '),
        "DefaultExperiment tolerance 'tight' is not a positive number"),
}


@pytest.fixture
def private_tmp(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """The folder extractions go to, for this test only."""
    folder = tmp_path / "extractions"
    folder.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(folder))
    monkeypatch.setenv(SIZE_LIMIT_VARIABLE, str(LIMIT))
    return folder


@pytest.mark.parametrize("case", list(CASES))
def test_every_loading_error_names_the_file_and_leaves_no_folder(case: str, tmp_path: Path,
                                                                 private_tmp: Path):
    build, expected = CASES[case]
    path = build(tmp_path)
    with pytest.raises(FMUFileError) as caught:
        FMUComponent("X", path)
    message = str(caught.value)
    assert str(path.resolve()) in message
    assert expected in message
    assert list(private_tmp.iterdir()) == []


def test_the_size_limit_must_be_a_number_of_bytes(monkeypatch: pytest.MonkeyPatch,
                                                  tmp_path: Path):
    # a copy of its own: a gain.fmu another test extracted is shared, not extracted again
    gain = tmp_path / "gain.fmu"
    shutil.copyfile(GAIN, gain)
    monkeypatch.setenv(SIZE_LIMIT_VARIABLE, "lots")
    with pytest.raises(ConfigurationError,
                       match=f"{gain}: cannot check the archive's size: {SIZE_LIMIT_VARIABLE}="
                             "'lots' is not a positive number of bytes"):
        FMUComponent("X", gain)


def test_the_size_limit_counts_declared_sizes_before_writing(tmp_path: Path, private_tmp: Path):
    # 300 000 zeros deflate to a few hundred bytes: the archive is small, its content is not
    path = oversized(tmp_path)
    assert path.stat().st_size < 150_000
    with pytest.raises(FMUFileError, match="raise it with SYSSIMX_FMU_SIZE_LIMIT"):
        FMUComponent("X", path)


def test_an_archive_within_the_limit_loads(tmp_path: Path, private_tmp: Path,
                                           monkeypatch: pytest.MonkeyPatch):
    monkeypatch.setenv(SIZE_LIMIT_VARIABLE, str(LIMIT + 300_000))
    component = FMUComponent("X", oversized(tmp_path))
    assert (component._unzip_dir / "resources" / "zeros.bin").stat().st_size == 300_000
    component.free()
    assert list(private_tmp.iterdir()) == []


def test_extraction_folders_are_removed_at_exit(tmp_path: Path):
    script = textwrap.dedent(f"""
        import tempfile
        tempfile.tempdir = {str(tmp_path)!r}
        from syssimx import FMUComponent, fmus
        kept = FMUComponent("kept", fmus.path("gain"))
        private = FMUComponent("private", fmus.path("pendulum_euler"))
        print(kept._unzip_dir, private._unzip_dir)
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=120, check=True)
    folders = [Path(p) for p in done.stdout.split()]
    assert len(folders) == 2 and all(f.parent == tmp_path for f in folders)
    assert list(tmp_path.iterdir()) == []


def test_fmi1_continuous_states_beyond_the_limit_are_refused(tmp_path: Path):
    """Before: OverflowError ("integer 3000000000 does not fit 'int'") when the engine
    allocated the states."""
    source = Path(fmus.path("pendulum_cvode_fmi1_me"))
    with zipfile.ZipFile(source) as archive:
        entries = {name: archive.read(name) for name in archive.namelist()}
    text, count = re.subn(rb'numberOfContinuousStates="\d+"',
                          b'numberOfContinuousStates="3000000000"', entries["modelDescription.xml"])
    assert count == 1
    path = write_archive(tmp_path / "states.fmu", {**entries, "modelDescription.xml": text})
    with pytest.raises(FMUFileError) as caught:
        FMUComponent("X", path)
    assert str(caught.value) == (f"{path.resolve()}: modelDescription.xml: "
                                 "numberOfContinuousStates='3000000000' is beyond syssimx's "
                                 "limit of 1000000")
