"""System.to_ssp: a System of FMU components written as an .ssp archive (SSP 1.0): the FMUs in
resources/, connectors, connections with their transformations, the parameters the user set
(inline parameter sets), the default experiment and the step as the Open Simulation Platform's
FixedStepAlgorithm annotation. The written structure is validated against the schema."""

from __future__ import annotations

import warnings
import zipfile
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, Protocol

from ..components.fmu import FMUComponent
from ..core.port import PortType
from .archive import SSD_NAME
from .documents import NS, tag, validate
from .errors import SSPError, SSPWarning
from .experiment import Experiment


class WrittenSystem(Protocol):
    """What the writer reads of a System."""

    name: str
    components: Mapping[str, Any]
    connections: Sequence[Any]
    event_connections: Sequence[Any]

OSP_NAMESPACE = "http://opensimulationplatform.com/SSP/OSPAnnotations"
OSP_TYPE = "com.opensimulationplatform"
_SSP_TYPE = {PortType.REAL: "Real", PortType.INT: "Integer", PortType.BOOL: "Boolean",
             PortType.STRING: "String", PortType.BINARY: "Binary"}


def write_ssp(system: WrittenSystem, path: str | Path,
              experiment: Experiment | None = None) -> Path:
    """Write `system` to the .ssp archive `path`; returns the path."""
    from lxml import etree

    path = Path(path)
    fmus = _fmu_files(system)
    _warn_events(system, path)
    # osp declared at the root: libcosim reads an attribute on osp:Algorithm as an algorithm
    namespaces = {**NS, "osp": OSP_NAMESPACE} if experiment and experiment.step_size else NS
    root = etree.Element(tag("ssd", "SystemStructureDescription"), nsmap=namespaces,
                         version="1.0", name=system.name)
    element = etree.SubElement(root, tag("ssd", "System"), name=system.name)
    elements = etree.SubElement(element, tag("ssd", "Elements"))
    for component in system.components.values():
        _component(elements, component, fmus[component.fmu_path])  # type: ignore[attr-defined]
    if system.connections:
        connections = etree.SubElement(element, tag("ssd", "Connections"))
        for c in system.connections:
            connection = etree.SubElement(connections, tag("ssd", "Connection"),
                                          startElement=c.src_comp, startConnector=c.src_port,
                                          endElement=c.dst_comp, endConnector=c.dst_port)
            if not c.convert_units:
                connection.set("suppressUnitConversion", "true")
            if (c.factor, c.offset) != (1.0, 0.0):
                etree.SubElement(connection, tag("ssc", "LinearTransformation"),
                                 factor=repr(c.factor), offset=repr(c.offset))
    if experiment is not None:
        _experiment(root, experiment)
    if not validate(root, "ssd"):
        raise SSPError(f"{path}: the structure written for {system.name!r} does not satisfy "
                       "the SSP schema")
    text = etree.tostring(root, xml_declaration=True, encoding="UTF-8", pretty_print=True)
    from ..atomic_file import atomic_path

    with atomic_path(path) as temporary, \
            zipfile.ZipFile(temporary, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr(SSD_NAME, text)
        for source, name in fmus.items():
            archive.write(source, name)
    return path


def _warn_events(system: WrittenSystem, path: Path) -> None:
    """SSP 1.0 has no events: what the system has of them is named, not written."""
    left_out = [f"event indicator {c.name}.{e}" for c in system.components.values()
                for e in c.event_indicators]
    left_out += ["event connection {}.{} -> {}.{}".format(*c.key())
                 for c in system.event_connections]
    if left_out:
        warnings.warn(f"{path}: SSP 1.0 has no events; not written: {', '.join(left_out)}",
                      SSPWarning, stacklevel=3)


def _fmu_files(system: WrittenSystem) -> dict[str, str]:
    """Each FMU file once, by its path, with its name in the archive."""
    names: dict[str, str] = {}
    for component in system.components.values():
        if not isinstance(component, FMUComponent):
            raise SSPError(f"{system.name}: component {component.name!r} is not an FMU; an "
                           "SSP holds FMU components only")
        if component.fmu_path not in names:
            stem, n = Path(component.fmu_path).stem, 1
            name = f"resources/{stem}.fmu"
            while name in names.values():
                n += 1
                name = f"resources/{stem}_{n}.fmu"
            names[component.fmu_path] = name
    return names


def _component(parent: Any, component: FMUComponent, source: str) -> None:
    from lxml import etree

    element = etree.SubElement(parent, tag("ssd", "Component"), name=component.name,
                               type="application/x-fmu-sharedlibrary", source=source)
    connectors = etree.SubElement(element, tag("ssd", "Connectors"))
    for kind, specs in (("input", component.input_specs), ("output", component.output_specs)):
        for name, spec in specs.items():
            if spec.type not in _SSP_TYPE:
                continue
            connector = etree.SubElement(connectors, tag("ssd", "Connector"), name=name,
                                         kind=kind)
            typed = etree.SubElement(connector, tag("ssc", _SSP_TYPE[spec.type]))
            if spec.unit:
                typed.set("unit", spec.unit)
    parameters = component.user_parameters()
    if not parameters:
        return
    bindings = etree.SubElement(element, tag("ssd", "ParameterBindings"))
    binding = etree.SubElement(bindings, tag("ssd", "ParameterBinding"))
    values = etree.SubElement(binding, tag("ssd", "ParameterValues"))
    parameter_set = etree.SubElement(values, tag("ssv", "ParameterSet"), version="1.0",
                                     name=component.name)
    listed = etree.SubElement(parameter_set, tag("ssv", "Parameters"))
    for name, value in parameters.items():
        declared = component.info.parameters[name]
        parameter = etree.SubElement(listed, tag("ssv", "Parameter"), name=name)
        kind = _SSP_TYPE[declared.type]
        text = str(value).lower() if isinstance(value, bool) else \
            repr(float(value)) if kind == "Real" else str(value)
        typed = etree.SubElement(parameter, tag("ssv", kind), value=text)
        if kind == "Real" and declared.unit:
            typed.set("unit", declared.unit)


def _experiment(root: Any, experiment: Experiment) -> None:
    from lxml import etree

    element = etree.SubElement(root, tag("ssd", "DefaultExperiment"))
    for attribute, value in (("startTime", experiment.start_time),
                             ("stopTime", experiment.stop_time)):
        if value is not None:
            element.set(attribute, repr(float(value)))
    if experiment.step_size is not None:
        annotations = etree.SubElement(element, tag("ssd", "Annotations"))
        annotation = etree.SubElement(annotations, tag("ssc", "Annotation"), type=OSP_TYPE)
        algorithm = etree.SubElement(annotation, f"{{{OSP_NAMESPACE}}}Algorithm")
        etree.SubElement(algorithm, f"{{{OSP_NAMESPACE}}}FixedStepAlgorithm",
                         baseStepSize=repr(float(experiment.step_size)))
