"""The SSP namespaces, safe XML parsing and validation against the SSP 1.0 schemas.

The schemas are those FMPy ships (fmpy/ssp/schema); lxml validates against them.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path
from typing import Any

from .errors import SSPError

NS = {
    "ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
    "ssc": "http://ssp-standard.org/SSP1/SystemStructureCommon",
    "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
    "ssm": "http://ssp-standard.org/SSP1/SystemStructureParameterMapping",
    "ssb": "http://ssp-standard.org/SSP1/SystemStructureSignalDictionary",
}
SCHEMAS = {
    "ssd": "SystemStructureDescription.xsd",
    "ssv": "SystemStructureParameterValues.xsd",
    "ssm": "SystemStructureParameterMapping.xsd",
    "ssb": "SystemStructureSignalDictionary.xsd",
}


def tag(prefix: str, name: str) -> str:
    """The qualified tag of `name` in the namespace `prefix`, as lxml spells it."""
    return f"{{{NS[prefix]}}}{name}"


def local_name(element: Any) -> str:
    return str(element.tag).rpartition("}")[2]


def parse(path: Path, kind: str, shown: str) -> Any:
    """The root element of the XML file at `path` (an .ssd, .ssv, .ssm or .ssb: `kind`),
    validated against its schema; errors name it as `shown`. No entities are resolved and
    nothing is fetched."""
    from lxml import etree

    if not path.is_file():
        raise SSPError(f"{shown}: file not found")
    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)
    try:
        root = etree.parse(str(path), parser).getroot()
    except (etree.XMLSyntaxError, OSError) as exc:
        raise SSPError(f"{shown}: malformed XML: {exc}") from exc
    try:
        valid = validate(root, kind)
    except etree.Error as exc:  # an entity left unresolved in content, for one
        raise SSPError(f"{shown}: cannot be checked against the SSP 1.0 schema "
                       f"({type(exc).__name__}: {exc}); entity references and DOCTYPE "
                       "declarations are not read in SSP files") from exc
    if not valid:
        errors = "; ".join(f"line {e.line}: {e.message}" for e in list(_schema(kind).error_log)[:3])
        raise SSPError(f"{shown}: not a valid {kind.upper()} file (SSP 1.0 schema): {errors}")
    return root


def validate(root: Any, kind: str) -> bool:
    """Whether the element tree `root` satisfies the SSP schema of `kind`."""
    return bool(_schema(kind).validate(root))


@cache
def _schema(kind: str) -> Any:
    from fmpy import ssp
    from lxml import etree

    directory = Path(ssp.__file__).parent / "schema"
    return etree.XMLSchema(file=str(directory / SCHEMAS[kind]))


def element_label(element: Any) -> str:
    """How an error names an element: its tag, its name attribute and its line."""
    name = element.get("name")
    named = f" {name!r}" if name else ""
    return f"<{local_name(element)}{named}> (line {element.sourceline})"
