"""The SSP namespaces, safe XML parsing and validation against the SSP 1.0 schemas.

The schemas are those FMPy ships (fmpy/ssp/schema); lxml validates against them. A file that
declares SSP 2.0 (OMSimulator 3 writes them, keeping the SSP 1.0 namespaces) is read as far as
it uses SSP 1.0 constructs: syssimx has no 2.0 schema, so each element or attribute the 1.0
schemas do not declare is one SSPWarning and left out, and the rest must satisfy the 1.0 schema.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path
from typing import Any

from .errors import SSPError
from .unsupported import Unsupported

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


def parse(path: Path, kind: str, shown: str, unsupported: Unsupported) -> Any:
    """The root element of the XML file at `path` (an .ssd, .ssv, .ssm or .ssb: `kind`),
    validated against its schema; errors name it as `shown`. No entities are resolved and
    nothing is fetched. An SSP 2.0 file comes back without what SSP 1.0 does not have."""
    from lxml import etree

    if not path.is_file():
        raise SSPError(f"{shown}: file not found")
    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)
    try:
        root = etree.parse(str(path), parser).getroot()
    except (etree.XMLSyntaxError, OSError) as exc:
        raise SSPError(f"{shown}: malformed XML: {exc}") from exc
    version = root.get("version", "")
    if version.startswith("2."):
        return _as_version_1(root, kind, shown, unsupported)
    if not _checked(root, kind, shown):
        raise SSPError(f"{shown}: not a valid {kind.upper()} file (SSP 1.0 schema): "
                       f"{_first_errors(kind)}")
    return root


def _checked(root: Any, kind: str, shown: str) -> bool:
    """Whether `root` satisfies the schema; a document the schema cannot check (an entity
    left unresolved in content, for one) is an SSPError naming the file."""
    from lxml import etree

    try:
        return validate(root, kind)
    except etree.Error as exc:
        raise SSPError(f"{shown}: cannot be checked against the SSP 1.0 schema "
                       f"({type(exc).__name__}: {exc}); entity references and DOCTYPE "
                       "declarations are not read in SSP files") from exc


def _first_errors(kind: str) -> str:
    return "; ".join(f"line {e.line}: {e.message}" for e in list(_schema(kind).error_log)[:3])


def _as_version_1(root: Any, kind: str, shown: str, unsupported: Unsupported) -> Any:
    """`root` (version 2.x) without the elements and attributes the SSP 1.0 schemas do not
    declare (one SSPWarning each), validated against the 1.0 schema."""
    elements, attributes = _declared_names()

    def prune(element: Any) -> None:
        for child in list(element):
            if not isinstance(child.tag, str):
                continue
            namespace, _, name = str(child.tag)[1:].partition("}")
            if namespace not in NS.values():
                continue  # another tool's annotation content: not SSP's to judge
            if name not in elements:
                unsupported.warn(f"SSP 2.0 element <{name}>",
                                 f"{shown}: {element_label(child)}, read as SSP 1.0")
                element.remove(child)
                continue
            for attribute in list(child.attrib):
                if "}" not in attribute and attribute not in attributes:
                    unsupported.warn(f"SSP 2.0 attribute {attribute!r}",
                                     f"{shown}: {element_label(child)}, read as SSP 1.0")
                    del child.attrib[attribute]
            prune(child)

    prune(root)
    version = root.get("version")
    root.set("version", "1.0")  # the pattern of the 1.0 schema: 1.x
    valid = _checked(root, kind, shown)
    root.set("version", version)
    if not valid:
        raise SSPError(f"{shown}: not a valid {kind.upper()} file (version {version} read as "
                       f"its SSP 1.0 constructs, against the SSP 1.0 schema): "
                       f"{_first_errors(kind)}")
    return root


@cache
def _declared_names() -> tuple[frozenset[str], frozenset[str]]:
    """The element and attribute names the SSP 1.0 schemas declare."""
    from lxml import etree

    elements: set[str] = set()
    attributes: set[str] = set()
    xs = "{http://www.w3.org/2001/XMLSchema}"
    for path in _schema_folder().glob("*.xsd"):
        tree = etree.parse(str(path))
        elements.update(e.get("name") for e in tree.iter(f"{xs}element") if e.get("name"))
        attributes.update(a.get("name") for a in tree.iter(f"{xs}attribute") if a.get("name"))
    return frozenset(elements), frozenset(attributes)


def _schema_folder() -> Path:
    from fmpy import ssp

    return Path(ssp.__file__).parent / "schema"


def validate(root: Any, kind: str) -> bool:
    """Whether the element tree `root` satisfies the SSP schema of `kind`."""
    return bool(_schema(kind).validate(root))


@cache
def _schema(kind: str) -> Any:
    from lxml import etree

    return etree.XMLSchema(file=str(_schema_folder() / SCHEMAS[kind]))


def element_label(element: Any) -> str:
    """How an error names an element: its tag, its name attribute and its line."""
    name = element.get("name")
    named = f" {name!r}" if name else ""
    return f"<{local_name(element)}{named}> (line {element.sourceline})"
