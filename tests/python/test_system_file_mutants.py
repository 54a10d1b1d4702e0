"""Users' SSD, SSV and OSP files, mutated: whatever an attribute or element becomes, reading
the file raises a SysSimXError (naming the file) or nothing, never another exception (before:
AttributeError for a parameter without a name, ValueError for a mapping's factor).

Each mutant changes one thing of a copy of a sample: an attribute removed or set to one of
VALUES, an element's text set to one of them, an element removed. The mutants are made in
document order, every STRIDE-th of them is read (all attribute removals are), so that the
test reads a few hundred files."""

from __future__ import annotations

import copy
import shutil
import warnings
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
from lxml import etree
from ssp_samples import available_samples
from syssimx.errors import SysSimXError
from syssimx.system_files import read_system_file

# (sample folder, the file read, the file mutated)
FILES = [
    ("omsimulator/LinearTransformation", "SystemStructure.ssd", "SystemStructure.ssd"),
    ("omsimulator/importParameterMappingInline", "SystemStructure.ssd", "SystemStructure.ssd"),
    ("omsimulator/toplevelparameter1", "SystemStructure.ssd", "resources/root.ssv"),
    ("omsimulator/import_export_parameters1", "SystemStructure.ssd",
     "resources/import_export_parameters.ssv"),
    ("libcosim/ssp/linear_transformation", "SystemStructure.ssd", "initial_values.ssv"),
    ("libcosim/msmi", "OspSystemStructure_Bond.xml", "OspSystemStructure_Bond.xml"),
]
VALUES = ("", "abc", "-1", "1e400", "nan", "3000000000", "a<b", "../../x", "/etc/passwd", ".",
          "a" * 300, "x\\")
STRIDE = 7

Mutation = Callable[[etree._ElementTree], None]


def _element(tree: etree._ElementTree, index: int) -> etree._Element:
    return list(tree.iter())[index]


def _set(index: int, attribute: str, value: str) -> Mutation:
    return lambda tree: _element(tree, index).set(attribute, value)


def _remove_attribute(index: int, attribute: str) -> Mutation:
    return lambda tree: _element(tree, index).attrib.pop(attribute)


def _text(index: int, value: str) -> Mutation:
    return lambda tree: setattr(_element(tree, index), "text", value)


def _remove(index: int) -> Mutation:
    def mutate(tree: etree._ElementTree) -> None:
        element = _element(tree, index)
        element.getparent().remove(element)
    return mutate


def _duplicate(index: int) -> Mutation:
    def mutate(tree: etree._ElementTree) -> None:
        element = _element(tree, index)
        element.getparent().append(copy.deepcopy(element))
    return mutate


def mutations(tree: etree._ElementTree) -> Iterator[tuple[str, Mutation, bool]]:
    """(what, how, always read) for each mutant of the document."""
    for index, element in enumerate(tree.iter()):
        if not isinstance(element.tag, str):
            continue  # a comment or processing instruction
        for attribute in element.attrib:
            yield f"remove {index}@{attribute}", _remove_attribute(index, attribute), True
            for value in VALUES:
                yield f"set {index}@{attribute}={value!r}", _set(index, attribute, value), False
        if element.text and element.text.strip():
            for value in VALUES:
                yield f"text {index}={value!r}", _text(index, value), False
        if index > 0:
            yield f"remove {index}", _remove(index), False
            yield f"duplicate {index}", _duplicate(index), False


@pytest.mark.parametrize(("folder", "read", "mutated"), FILES,
                         ids=[f"{folder}/{mutated}" for folder, _, mutated in FILES])
def test_every_mutant_is_read_or_refused_with_a_syssimx_error(tmp_path: Path, folder: str,
                                                              read: str, mutated: str):
    source = available_samples() / folder
    copied = tmp_path / "copy"
    shutil.copytree(source, copied)
    original = etree.parse(str(source / mutated))
    others: list[str] = []
    count = 0
    for number, (what, mutate, always) in enumerate(mutations(original)):
        if not always and number % STRIDE:
            continue
        tree = copy.deepcopy(original)
        mutate(tree)
        tree.write(str(copied / mutated), xml_declaration=True, encoding="UTF-8")
        count += 1
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                read_system_file(copied / read)
        except SysSimXError:
            pass
        except Exception as error:  # what this test is for: any other kind is a defect
            others.append(f"{what}: {type(error).__name__}: {error}")
    assert count >= 10
    assert others == []


def test_a_mapping_factor_that_is_no_number_is_an_ssp_error(tmp_path: Path):
    """Before: float()'s ValueError."""
    from syssimx.ssp import SSPError

    copied = tmp_path / "copy"
    shutil.copytree(available_samples() / "omsimulator/importParameterMappingInline", copied)
    path = copied / "SystemStructure.ssd"
    entry = '<ssm:MappingEntry source="cosim_inputs" target="Input_1" />'
    text = path.read_text()
    assert entry in text
    path.write_text(text.replace(entry, '<ssm:MappingEntry source="cosim_inputs" '
                                        'target="Input_1"><ssc:LinearTransformation '
                                        'factor="abc"/></ssm:MappingEntry>', 1))
    with pytest.raises(SSPError) as caught:
        read_system_file(path)
    assert str(caught.value) == (f"{path}: <MappingEntry> (line 46): LinearTransformation "
                                 "factor 'abc' is not a number")
