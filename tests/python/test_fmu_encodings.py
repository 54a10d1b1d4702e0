"""A modelDescription in any encoding Python knows is read: 20-sim's ISO-8859-1 FMUs (libcosim's
crane) run equal to FMPy on the same grid; a bundled FMU rewritten as windows-1252 or UTF-16
reads the same texts; bytes invalid in the declared encoding are refused with the file and the
offset."""

from __future__ import annotations

import codecs
import re
import shutil
import zipfile
from pathlib import Path

import numpy as np
import pytest
from fmpy import simulate_fmu
from samples_root import samples_root
from syssimx import FMUComponent, System, fmus
from syssimx.errors import FMUFileError

CRANE = samples_root() / "libcosim" / "fmi2"
DESCRIPTION = "Verstärkung \u2013 «gain» 5 €"  # in windows-1252, not in ISO-8859-1 (dash, €)


def crane(name: str) -> Path:
    path = CRANE / f"{name}.fmu"
    if not path.is_file():
        pytest.skip(f"libcosim's 20-sim crane FMUs are absent ({path}): set SYSSIMX_SSP_SAMPLES")
    return path


# inputs held constant over the run; the crane alone (no controller holding it) falls and its
# model breaks down after 1.27 s, so runs stop at 1 s
CRANE_INPUTS = {
    "KnuckleBoomCrane": {"p_Crane.e[1]": 0.2, "p_Crane.e[2]": -0.1, "p_Crane.e[3]": 0.05},
    "CraneController": {"Motor": 0.5, "Cylinder1": -0.3, "Cylinder2": 0.2,
                        "p_Crane.f[1]": 0.01, "p_Crane.f[2]": 0.02, "p_Crane.f[3]": -0.01},
}


@pytest.mark.parametrize("name", sorted(CRANE_INPUTS))
def test_iso_8859_1_crane_runs_equal_to_fmpy(name: str):
    path = crane(name)
    with zipfile.ZipFile(path) as archive:
        assert archive.read("modelDescription.xml").startswith(
            b'<?xml version="1.0" encoding="ISO-8859-1"?>')
    inputs = CRANE_INPUTS[name]
    component = FMUComponent("C", path)
    outputs = sorted(component.output_specs)
    reference = simulate_fmu(str(path), start_time=0.0, stop_time=1.0, output_interval=0.01,
                             start_values=inputs, output=outputs)
    component.set_inputs(inputs)
    system = System("crane")
    system.add_component(component)
    system.initialize(0.0)
    t, values = system.run(0.0, 1.0, 0.01)["C"]
    np.testing.assert_allclose(t, reference["time"], rtol=0, atol=1e-12)
    moved = 0
    for port in outputs:
        # the same binary on the same grid with the same inputs: identical numbers
        np.testing.assert_array_equal(values[port], reference[port], err_msg=port)
        moved += np.ptp(values[port]) > 0
    assert moved >= 3  # the comparison is about trajectories, not constants


def reencoded(tmp_path: Path, encoding: str, raw: bytes | None = None) -> Path:
    """A copy of the bundled gain FMU whose modelDescription declares `encoding`, its
    description attribute set to DESCRIPTION, written in that encoding (or `raw` as is)."""
    source = Path(fmus.path("gain"))
    target = tmp_path / f"gain-{encoding}.fmu"
    with zipfile.ZipFile(source) as original, zipfile.ZipFile(target, "w") as copy:
        for item in original.infolist():
            data = original.read(item)
            if item.filename == "modelDescription.xml":
                text = data.decode("utf-8").replace('encoding="UTF-8"', f'encoding="{encoding}"')
                text = re.sub(r'description="[^"]*"', f'description="{DESCRIPTION}"', text,
                              count=1)
                data = raw if raw is not None else text.encode(encoding)
                if encoding.upper() == "UTF-16" and raw is None:
                    assert data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE))
            copy.writestr(item, data)
    return target


@pytest.mark.parametrize("encoding", ["windows-1252", "UTF-16"])
def test_reencoded_description_reads_the_same_and_runs(tmp_path: Path, encoding: str):
    path = reencoded(tmp_path, encoding)
    gain = FMUComponent("G", path)
    assert gain.info.description.description == DESCRIPTION
    bundled = FMUComponent("B", fmus.path("gain"))
    assert sorted(gain.input_specs) == sorted(bundled.input_specs) == ["u"]
    assert gain.parameters == bundled.parameters
    gain.set_parameters(k=3.0)
    gain.set_inputs({"u": 2.0})
    gain.initialize(0.0)
    assert gain.get_outputs()["y"].magnitude == 6.0


def test_bytes_invalid_in_the_declared_encoding_are_refused_naming_file_and_offset(
        tmp_path: Path):
    text = zipfile.ZipFile(fmus.path("gain")).read("modelDescription.xml").decode()
    text = text.replace('encoding="UTF-8"', 'encoding="windows-1252"')
    data = text.encode("ascii")
    offset = data.index(b"Static gain")
    # 0x81 is no character of windows-1252
    broken = data[:offset] + b"\x81" + data[offset + 1:]
    path = reencoded(tmp_path, "windows-1252", raw=broken)
    with pytest.raises(FMUFileError, match=rf"^{re.escape(str(path.resolve()))}: "
                       rf"modelDescription\.xml: byte\(s\) 81 at offset {offset} are not valid "
                       r"WINDOWS-1252, the encoding the file declares$"):
        FMUComponent("G", path)


def test_an_encoding_python_does_not_know_is_named(tmp_path: Path):
    path = reencoded(tmp_path, "x-klingon", raw=zipfile.ZipFile(fmus.path("gain")).read(
        "modelDescription.xml").replace(b'encoding="UTF-8"', b'encoding="x-klingon"'))
    with pytest.raises(FMUFileError, match=r"names the encoding 'x-klingon', which Python does "
                       "not know"):
        FMUComponent("G", path)


def test_a_transform_is_no_file_encoding(tmp_path: Path):
    data = zipfile.ZipFile(fmus.path("gain")).read("modelDescription.xml")
    path = reencoded(tmp_path, "unicode_escape", raw=data.replace(b'encoding="UTF-8"',
                                                         b'encoding="unicode_escape"'))
    with pytest.raises(FMUFileError, match="'unicode_escape', which is not a character encoding"):
        FMUComponent("G", path)


def test_utf8_files_pass_untouched(tmp_path: Path):
    shutil.copyfile(fmus.path("gain"), tmp_path / "gain.fmu")
    assert FMUComponent("G", tmp_path / "gain.fmu").info.description.description.startswith(
        "Static gain")


@pytest.mark.parametrize("encoding", ["ISO-8859-1", "windows-1252", "UTF-16", "shift_jis"])
def test_mutated_bytes_in_any_encoding_are_read_or_refused_by_name(encoding: str):
    """Random bytes written over a description that declares `encoding`: each mutant is read
    or refused with an FMUFileError naming the file, never another exception."""
    import io
    import random

    from syssimx.fmu.description import read_description

    text = zipfile.ZipFile(fmus.path("gain")).read("modelDescription.xml").decode()
    data = text.replace('encoding="UTF-8"', f'encoding="{encoding}"').encode(encoding)
    rng = random.Random(20261125)
    outcomes = {"read": 0, "refused": 0}
    for _ in range(300):
        mutant = bytearray(data)
        for _ in range(rng.randint(1, 4)):
            at = rng.randrange(len(mutant))
            mutant[at:at + rng.randint(1, 3)] = bytes(rng.randrange(256)
                                                       for _ in range(rng.randint(0, 3)))
        try:
            read_description(io.BytesIO(bytes(mutant)), "m.fmu")
            outcomes["read"] += 1
        except FMUFileError as error:
            assert str(error).startswith("m.fmu: ")
            outcomes["refused"] += 1
    assert outcomes["read"] > 0 and outcomes["refused"] > 0
