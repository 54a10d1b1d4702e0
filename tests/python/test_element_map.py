"""ElementMap: a dict whose array elements are made at their first lookup."""

from __future__ import annotations

import copy

import pytest
from syssimx.core.element_map import Block, ElementMap, made_items


def counting_map() -> tuple[ElementMap[tuple[int, str]], list[int]]:
    made: list[int] = []

    def make(position: int, name: str) -> tuple[int, str]:
        made.append(position)
        return position, name

    return ElementMap.in_order([("u", "scalar"), Block("m", (2, 3), make), ("y", "last")]), made


def test_names_keep_their_order_and_elements_are_made_once_when_asked():
    elements, made = counting_map()
    assert len(elements) == 8
    assert list(elements) == ["u", "m[0,0]", "m[0,1]", "m[0,2]", "m[1,0]", "m[1,1]", "m[1,2]",
                              "y"]
    assert made == [] and "m[1,2]" in elements and made == []
    assert elements["m[1,2]"] == (5, "m[1,2]") and elements["m[1,2]"] == (5, "m[1,2]")
    assert made == [5]
    assert made_items(elements) == {"u": "scalar", "y": "last", "m[1,2]": (5, "m[1,2]")}
    for name in ("m[2,0]", "m[0]", "m", "m[0,01]", "m[0,-1]", "m[0, 1]", "m[0,1"):
        assert name not in elements and elements.get(name) is None, name


def test_set_delete_and_copies_are_those_of_a_dict():
    elements, made = counting_map()
    elements["m[0,1]"] = (0, "set")
    elements["z"] = (9, "new")
    del elements["m[1,0]"]
    del elements["u"]
    assert list(elements) == ["m[0,0]", "m[0,1]", "m[0,2]", "m[1,1]", "m[1,2]", "y", "z"]
    assert len(elements) == 7 and made == []
    with pytest.raises(KeyError):
        elements["m[1,0]"]
    twin = copy.copy(elements)
    twin["m[0,0]"] = (0, "twin's")
    assert elements["m[0,0]"] == (0, "m[0,0]") and twin["m[0,0]"] == (0, "twin's")
    deep = copy.deepcopy(elements)
    assert dict(deep) == dict(elements)
    names = elements.mapped(lambda name, value: value[1].upper())
    assert names["m[1,2]"] == "M[1,2]" and names["m[0,1]"] == "SET"
    assert list(names) == list(elements)
