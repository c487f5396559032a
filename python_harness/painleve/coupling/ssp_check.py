# SPDX-License-Identifier: BSD-2-Clause
"""Validation of an SSP archive: what fmpy 0.3.32 offers, and the consistency it leaves out.

fmpy's SSP support (fmpy.ssp) has no `validate` command: `fmpy validate` reads FMUs only,
and fmpy.ssp.ssd.read_ssd(path, validate=True) checks SystemStructure.ssd against the
SSP 1.0 XML schema it ships (fmpy/ssp/schema) and parses it. fmpy.validation.validate_fmu
checks each FMU. Neither looks across the two, so `check_ssp` adds what the SSP 1.0
standard states (SystemStructureDescription.xsd's own documentation):
- a component's connectors "must match variables of the underlying FMU by name", and a
  connector's type, when given, must be that variable's type;
- a connection runs from an output to an input (component to component);
- here also: each connected input has exactly one source, a connector's kind is the
  variable's causality, a parameter binding names a variable whose start value may be set
  (a parameter, or a variable with initial="exact"), inside its min/max, and a connection
  joins two variables of the same unit.
"""
from __future__ import annotations

import shutil
import tempfile
import zipfile

from .ssp import SSD_NAME, start_values

SETTABLE = ("parameter", "input")     # causalities whose start value a binding may set


def check_ssp(ssp_path):
    """The problems found (an empty list: the archive is valid)."""
    from fmpy import read_model_description
    from fmpy.ssp.ssd import Component, read_ssd
    from fmpy.validation import validate_fmu
    problems = []
    try:
        ssd = read_ssd(str(ssp_path), validate=True)     # the SSP 1.0 schema
    except Exception as err:
        return [f"{SSD_NAME}: {' '.join(str(err).split())}"]
    with zipfile.ZipFile(ssp_path) as archive:
        names = set(archive.namelist())
        work = tempfile.mkdtemp(prefix="painleve-ssp-check-")
        try:
            variables = {}
            for comp in ssd.system.elements:
                if not isinstance(comp, Component):
                    continue
                if comp.source not in names:
                    problems.append(f"{comp.name}: its source {comp.source} is not in the archive")
                    continue
                fmu = archive.extract(comp.source, work)
                problems += [f"{comp.source}: {p}" for p in validate_fmu(fmu)]
                md = read_model_description(fmu, validate=False)
                if md.coSimulation is None:
                    problems.append(f"{comp.name}: {comp.source} has no Co-Simulation interface")
                variables[comp.name] = {v.name: v for v in md.modelVariables}
                for connector in comp.connectors:
                    v = variables[comp.name].get(connector.name)
                    if v is None:
                        problems.append(f"{comp.name}.{connector.name}: {comp.source} has no such variable")
                    elif v.causality != connector.kind:
                        problems.append(f"{comp.name}.{connector.name}: connector kind {connector.kind}, "
                                        f"but the variable's causality is {v.causality}")
        finally:
            shutil.rmtree(work, ignore_errors=True)
    problems += _connection_problems(ssd, variables)
    problems += _binding_problems(ssp_path, variables)
    return problems


def _connection_problems(ssd, variables):
    problems, sources = [], {}
    connectors = {(c.parent.name, c.name): c for el in ssd.system.elements for c in el.connectors}
    for con in ssd.system.connections:
        start, end = (con.startElement, con.startConnector), (con.endElement, con.endConnector)
        label = f"connection {'.'.join(map(str, start))} -> {'.'.join(map(str, end))}"
        if start not in connectors or end not in connectors:
            missing = start if start not in connectors else end
            problems.append(f"{label}: no connector {'.'.join(map(str, missing))}")
            continue
        if connectors[start].kind != "output" or connectors[end].kind != "input":
            problems.append(f"{label}: runs from kind {connectors[start].kind} to kind {connectors[end].kind} "
                            f"(SSP 1.0: from an output to an input)")
        sources.setdefault(end, []).append(start)
        a, b = variables.get(start[0], {}).get(start[1]), variables.get(end[0], {}).get(end[1])
        if a is not None and b is not None:
            if a.type != b.type:
                problems.append(f"{label}: joins a {a.type} to a {b.type}")
            if _unit(a) != _unit(b):
                problems.append(f"{label}: joins unit {_unit(a)!r} to unit {_unit(b)!r}")
    for (comp, name), c in connectors.items():
        if c.kind == "input" and len(sources.get((comp, name), [])) != 1:
            problems.append(f"{comp}.{name}: an input connector with {len(sources.get((comp, name), []))} "
                            f"connections (one needed)")
    return problems


def _binding_problems(ssp_path, variables):
    problems = []
    for comp, values in start_values(ssp_path).items():
        for name, value in values.items():
            v = variables.get(comp, {}).get(name)
            if v is None:
                problems.append(f"{comp}.{name}: bound, but the FMU has no such variable")
                continue
            if v.causality not in SETTABLE and v.initial != "exact":
                problems.append(f"{comp}.{name}: bound, but its start value cannot be set "
                                f"(causality {v.causality}, initial {v.initial})")
            lo, hi = _float(v.min), _float(v.max)
            if (lo is not None and value < lo) or (hi is not None and value > hi):
                problems.append(f"{comp}.{name} = {value!r}: outside [{v.min}, {v.max}]")
    return problems


def _float(text):
    return None if text in (None, "") else float(text)


def _unit(v):
    """A variable's unit, its own or its declared type's."""
    return v.unit or (v.declaredType.unit if v.declaredType is not None else None)
