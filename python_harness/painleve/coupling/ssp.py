# SPDX-License-Identifier: BSD-2-Clause
"""An SSP 1.0 archive (System Structure and Parameterization, ssp-standard.org) written from
built FMUs: `SystemStructure.ssd` and `resources/NAME.fmu`, zipped into one `.ssp` file.

The archive is generated, never committed: the FMUs inside are this machine's build. A
component names its FMU, the start values bound to it (an inline `ssv:ParameterSet`, which
libcosim and ecos apply; fmpy's simulate_ssp takes them as its `parameter_set`, see
`parameter_set`) and its connectors: every connected input and every output a master should
record (fmpy's simulate_ssp records connectors only, and fails on an input without a
connection, so no unconnected input is declared). A connection runs from an output to an
input, as SSP 1.0 says information flows (SystemStructureDescription.xsd, Connection).
"""
from __future__ import annotations

import pathlib
import zipfile
from dataclasses import dataclass, field

from lxml import etree

NS = {
    "ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
    "ssc": "http://ssp-standard.org/SSP1/SystemStructureCommon",
    "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
}
SSD_NAME = "SystemStructure.ssd"
START_VALUES = "start values"     # the one name of every component's parameter set (ecos applies a set by name)


@dataclass
class Component:
    """One FMU instance: its name in the system, the FMU file, start values (name -> number),
    and the variables the system sees (inputs connected to, outputs recorded or connected)."""
    name: str
    fmu: str | pathlib.Path
    start_values: dict = field(default_factory=dict)
    inputs: tuple = ()
    outputs: tuple = ()

    @property
    def source(self):
        """Where the FMU lies inside the archive."""
        return f"resources/{pathlib.Path(self.fmu).name}"


@dataclass(frozen=True)
class Connection:
    """start = (component, output) feeds end = (component, input)."""
    start: tuple
    end: tuple


def _q(prefix, tag):
    return f"{{{NS[prefix]}}}{tag}"


def _number(x):
    """A start value as SSP writes an xs:double: repr, exact for a Python float."""
    return repr(float(x))


def _types(fmu):
    """{variable: SSP connector type} of an FMU (libcosim requires the type on every connector);
    SSP 1.0 names FMI 3.0's Float64 and Int32 Real and Integer, as FMI 2.0's."""
    from fmpy import read_model_description
    return {v.name: {"Enumeration": "Integer", "Float64": "Real", "Int32": "Integer"}.get(v.type, v.type)
            for v in read_model_description(str(fmu)).modelVariables}


def ssd_tree(name, components, connections, *, start_time=0.0, stop_time=1.0):
    """The SystemStructure.ssd of the system (an lxml element)."""
    root = etree.Element(_q("ssd", "SystemStructureDescription"), nsmap=NS, version="1.0", name=name)
    system = etree.SubElement(root, _q("ssd", "System"), name=name)
    elements = etree.SubElement(system, _q("ssd", "Elements"))
    for comp in components:
        el = etree.SubElement(elements, _q("ssd", "Component"), name=comp.name, source=comp.source,
                              type="application/x-fmu-sharedlibrary")
        connectors = [(n, "input") for n in comp.inputs] + [(n, "output") for n in comp.outputs]
        if connectors:
            types = _types(comp.fmu)
            box = etree.SubElement(el, _q("ssd", "Connectors"))
            for var, kind in connectors:
                if var not in types:
                    raise ValueError(f"{comp.fmu} has no variable {var!r} (component {comp.name})")
                connector = etree.SubElement(box, _q("ssd", "Connector"), name=var, kind=kind)
                etree.SubElement(connector, _q("ssc", types[var]))
        if comp.start_values:
            bindings = etree.SubElement(el, _q("ssd", "ParameterBindings"))
            binding = etree.SubElement(bindings, _q("ssd", "ParameterBinding"))
            values = etree.SubElement(binding, _q("ssd", "ParameterValues"))
            pset = etree.SubElement(values, _q("ssv", "ParameterSet"), version="1.0", name=START_VALUES)
            params = etree.SubElement(pset, _q("ssv", "Parameters"))
            for var, value in comp.start_values.items():
                p = etree.SubElement(params, _q("ssv", "Parameter"), name=var)
                etree.SubElement(p, _q("ssv", "Real"), value=_number(value))
    if connections:
        box = etree.SubElement(system, _q("ssd", "Connections"))
        for c in connections:
            etree.SubElement(box, _q("ssd", "Connection"), startElement=c.start[0], startConnector=c.start[1],
                             endElement=c.end[0], endConnector=c.end[1])
    etree.SubElement(root, _q("ssd", "DefaultExperiment"), startTime=_number(start_time), stopTime=_number(stop_time))
    return root


def write_ssp(path, name, components, connections=(), *, start_time=0.0, stop_time=1.0):
    """Writes the .ssp archive at `path` (SystemStructure.ssd and each distinct FMU once under
    resources/); returns the path."""
    sources = {}
    for comp in components:
        known = sources.setdefault(comp.source, pathlib.Path(comp.fmu))
        if known.resolve() != pathlib.Path(comp.fmu).resolve():
            raise ValueError(f"two FMUs would be {comp.source}: {known} and {comp.fmu}")
    tree = ssd_tree(name, components, connections, start_time=start_time, stop_time=stop_time)
    xml = etree.tostring(tree, xml_declaration=True, encoding="UTF-8", pretty_print=True)
    path = pathlib.Path(path)
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as ssp:
        ssp.writestr(SSD_NAME, xml)
        for source, fmu in sources.items():
            ssp.write(fmu, source)
    return path


def extract_ssp(path, directory):
    """Unzips the archive into `directory` (libcosim reads an SSP from a directory)."""
    with zipfile.ZipFile(path) as ssp:
        ssp.extractall(directory)
    return pathlib.Path(directory)


def start_values(ssp_path):
    """{component: {variable: value}} from the archive's inline parameter bindings, read by
    fmpy's SSP reader (which also validates the .ssd against the SSP 1.0 schema)."""
    from fmpy.ssp.ssd import Component as SspComponent, read_ssd
    ssd = read_ssd(str(ssp_path), validate=True)
    values = {}
    for element in ssd.system.elements:
        if isinstance(element, SspComponent):
            mine = values.setdefault(element.name, {})
            for binding in element.parameterBindings:
                for pset in binding.parameterValues:
                    for p in pset.parameters:
                        mine[p.name] = float(p.value)
    return values


def parameter_set(ssp_path):
    """The archive's start values as the one fmpy ParameterSet that fmpy.ssp.simulation.simulate_ssp
    takes (it reads no ParameterBindings from the .ssd itself): names 'component.variable'."""
    from fmpy.ssp.ssd import Parameter, ParameterSet
    pset = ParameterSet(name="start values")
    for comp, values in start_values(ssp_path).items():
        for var, value in values.items():
            pset.parameters.append(Parameter(name=f"{comp}.{var}", type="Real", value=repr(value)))
    return pset
