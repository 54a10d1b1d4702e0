"""Hostile modelDescriptions (issue 20's second round), built here by editing the bundled FMUs:
each is an FMUFileError naming the file and the variable, before anything is sized by it, and
never a crash, a bare ValueError, OverflowError or MemoryError."""

from __future__ import annotations

import random
import subprocess
import sys
import time
import zipfile
from pathlib import Path

import pytest
from syssimx import FMUComponent, fmus
from syssimx.cli import main
from syssimx.errors import ConfigurationError, FMUFileError
from syssimx.fmu.description_fmi2 import MAX_EVENT_INDICATORS
from syssimx.fmu.description_fmi3 import MAX_ARRAY_ELEMENTS

GAIN3 = Path(fmus.path("gain_fmi3"))
GAIN2 = Path(fmus.path("gain"))
K = ('<Float64 name="k" valueReference="2" causality="parameter" variability="fixed" '
     'initial="exact" description="gain" start="1"/>')
STRUCTURAL = ('<{type} name="n" valueReference="9" causality="structuralParameter" '
              'variability="fixed" start="{n}"/>')


def entries(fmu: Path) -> dict[str, bytes]:
    with zipfile.ZipFile(fmu) as archive:
        return {name: archive.read(name) for name in archive.namelist()}


def with_description(tmp_path: Path, fmu: Path, text: str | bytes, name: str = "edited"
                     ) -> Path:
    data = text.encode() if isinstance(text, str) else text
    path = tmp_path / f"{name}.fmu"
    with zipfile.ZipFile(path, "w") as archive:
        for entry, content in {**entries(fmu), "modelDescription.xml": data}.items():
            archive.writestr(entry, content)
    return path


def gain3_with(tmp_path: Path, replacement: str) -> Path:
    """gain_fmi3 with its parameter k replaced (ModelStructure no longer names k)."""
    text = entries(GAIN3)["modelDescription.xml"].decode()
    assert K in text
    text = text.replace(K, replacement).replace(' dependencies="1 2"', ' dependencies="1"')
    return with_description(tmp_path, GAIN3, text)


def refused(path: Path, *parts: str) -> str:
    with pytest.raises(FMUFileError) as caught:
        FMUComponent("G", str(path))
    message = str(caught.value)
    assert message.startswith(str(path)), message
    for part in parts:
        assert part in message, message
    return message


def test_an_end_tag_where_the_root_belongs_is_refused_in_every_front_end(tmp_path: Path):
    """Before: SIGSEGV in the C reader (it read the element stack below its bottom)."""
    path = with_description(tmp_path, GAIN2, "</a>")
    script = ("import sys\nfrom syssimx import FMUComponent\nfrom syssimx.errors import "
              "FMUFileError\ntry:\n    FMUComponent('G', sys.argv[1], isolated=True)\n"
              "except FMUFileError as e:\n    print(e)\n")
    done = subprocess.run([sys.executable, "-c", script, str(path)], capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "end tag </a> without a start tag" in done.stdout
    for command in (["info", str(path)], ["simulate", str(path), "--stop-time", "0.1"]):
        done = subprocess.run([sys.executable, "-c", "import sys; from syssimx.cli import main;"
                               " sys.exit(main(sys.argv[1:]))", *command],
                              capture_output=True, text=True, timeout=120)
        assert done.returncode not in (0, -11), done.stderr  # refused, not a SIGSEGV
        assert str(path) in done.stderr and "Traceback" not in done.stderr


@pytest.mark.parametrize(("replacement", "parts"), [
    (K.replace('start="1"', 'start="abc"'), ["'k'", "start 'abc' is not a Float64 value"]),
    ('<Int32 name="k" valueReference="2" causality="parameter" variability="fixed" '
     'start="1.5"/>', ["'k'", "start '1.5' is not a Int32 value"]),
    ('<UInt8 name="k" valueReference="2" causality="parameter" variability="fixed" '
     'start="256"/>', ["'k'", "start '256' is not a UInt8 value"]),
    ('<Binary name="k" valueReference="2" causality="parameter" variability="fixed">'
     '<Start value="abc"/></Binary>', ["'k'", "not an even number of hexadecimal digits"]),
    (K.replace('start="1"/>', 'start="1 x"><Dimension start="2"/></Float64>'),
     ["'k'", "start 'x' is not a Float64 value"]),
    (K.replace('valueReference="2"', 'valueReference="4294967296"'),
     ["'k'", "valueReference 4294967296", "0 to 4294967295"]),
    (K.replace('valueReference="2"', 'valueReference="-1"'), ["'k'", "valueReference -1"]),
    (K.replace('start="1"/>', 'start="1"><Dimension start="-3"/></Float64>'),
     ["'k'", "dimension of -3 (from its start)"]),
    (STRUCTURAL.format(type="Int64", n=-2) + K.replace('start="1"/>', 'start="1"><Dimension '
                                                       'valueReference="9"/></Float64>'),
     ["'k'", "dimension of -2 (from structural parameter 'n')"]),
    (STRUCTURAL.format(type="UInt64", n=-2) + K.replace('start="1"/>', 'start="1"><Dimension '
                                                        'valueReference="9"/></Float64>'),
     ["'n'", "start '-2' is not a UInt64 value"]),
])
def test_a_bad_fmi3_variable_is_named(tmp_path: Path, replacement: str, parts: list[str]):
    refused(gain3_with(tmp_path, replacement), *parts)


def test_an_fmi3_array_beyond_the_limit_is_refused_at_once(tmp_path: Path):
    """Before: a 2 KB file ended in MemoryError after a minute (one object per element)."""
    huge = K.replace('start="1"/>', '><Dimension start="100000000"/></Float64>')
    started = time.process_time()
    refused(gain3_with(tmp_path, huge), "'k'", "(100000000,)", f"limit of {MAX_ARRAY_ELEMENTS}")
    assert time.process_time() - started < 5


def test_an_fmi3_array_at_the_limit_is_read(tmp_path: Path):
    """The limit is a limit, not a refusal of arrays: a local array of the limit's size reads
    (locals are no ports, so this stays cheap)."""
    local = ('<Float64 name="k" valueReference="2" causality="local" variability="continuous">'
             f'<Dimension start="{MAX_ARRAY_ELEMENTS}"/></Float64>')
    component = FMUComponent("G", str(gain3_with(tmp_path, local)))
    assert "y" in component.outputs


@pytest.mark.parametrize("count", ["3000000000", str(MAX_EVENT_INDICATORS + 1), "100000000"])
def test_too_many_fmi2_event_indicators_are_refused_before_allocation(tmp_path: Path,
                                                                      count: str):
    text = entries(GAIN2)["modelDescription.xml"].decode()
    assert 'numberOfEventIndicators="0"' in text
    text = text.replace('numberOfEventIndicators="0"', f'numberOfEventIndicators="{count}"')
    path = with_description(tmp_path, GAIN2, text)
    with pytest.raises(FMUFileError, match=f"numberOfEventIndicators='{count}' is beyond "
                       f"syssimx's limit of {MAX_EVENT_INDICATORS}"):
        FMUComponent("G", str(path), interface="model-exchange")


def test_the_command_line_names_a_bad_fmi3_file(tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str]):
    path = gain3_with(tmp_path, K.replace('start="1"', 'start="abc"'))
    assert main(["simulate", str(path), "--stop-time", "0.1"]) != 0
    error = capsys.readouterr().err
    assert str(path) in error and "Traceback" not in error


def mutants(text: bytes, count: int, seed: int) -> list[bytes]:
    """Deterministic mutations of a description: bytes replaced by markup characters, spans
    removed or repeated, digits changed, the text cut short."""
    generator = random.Random(seed)
    special = b'<>&;#"\'/=!?-[] \n0123456789-e.x'
    out = []
    for _ in range(count):
        data = bytearray(text)
        for _ in range(generator.randint(1, 3)):
            at = generator.randrange(len(data))
            span = generator.randint(1, 24)
            action = generator.randrange(5)
            if action == 0:
                data[at] = special[generator.randrange(len(special))]
            elif action == 1:
                del data[at:at + span]
            elif action == 2:
                data[at:at] = data[at:at + span]
            elif action == 3:
                data[at] = generator.randrange(256)
            else:
                del data[at:]
            if not data:
                data = bytearray(b"<")
        out.append(bytes(data))
    return out


@pytest.mark.parametrize(("stem", "interface"), [("gain_fmi3", "auto"),
                                                 ("bouncing_ball_cvode_fmi3", "model-exchange")])
def test_mutated_fmi3_descriptions_raise_only_fmu_file_errors(tmp_path: Path, stem: str,
                                                              interface: str):
    """The FMI 3.0 description path is Python (FMPy's reader over lxml, then our checks): a
    bounded mutation run where each input is read or refused with FMUFileError, nothing else
    (the C reader of FMI 2.0 is fuzzed with libFuzzer: scripts/fuzz.sh). The seeds: a static
    gain, and a ball with states and an event indicator read as Model Exchange (a mutant that
    lost its ModelExchange element is a ConfigurationError naming the file and interface)."""
    fmu = Path(fmus.path(stem))
    text = entries(fmu)["modelDescription.xml"]
    refusals = 0
    for k, data in enumerate(mutants(text, 300, seed=20)):
        path = with_description(tmp_path, fmu, data, name=f"mutant{k}")
        try:
            FMUComponent("G", str(path), interface=interface)
        except FMUFileError:
            refusals += 1
        except ConfigurationError as exc:  # the interface asked for is gone: named as such
            assert path.name in str(exc) and "interface" in str(exc), exc
            refusals += 1
        except Exception as exc:  # the point: nothing else escapes
            pytest.fail(f"mutant {k} raised {type(exc).__name__}: {exc}\n{data.decode('latin-1')}")
        finally:
            path.unlink()
    assert 50 < refusals < 300  # both outcomes exercised
