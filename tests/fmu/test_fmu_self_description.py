# SPDX-License-Identifier: BSD-2-Clause
"""The FMU describes itself: units (rad for angles, a named dimensionless unit for
the rest, the paper's scales), a stepSize in the DefaultExperiment, and documentation/index.html
made from the model's variables; in the FMI 2.0 FMU and in the FMI 3.0 one, whose model
description the build makes from the FMI 2.0 one."""
import html.parser
import xml.etree.ElementTree as ET
import zipfile

import fmpy
import pytest

ANGLES = {"theta"}                          # the rod's angle, rad
ANGULAR_RATES = {"phi", "der(theta)"}       # rad per unit of time
DIMENSIONLESS = "dimensionless"


def description(fmu):
    with zipfile.ZipFile(fmu) as z:
        return ET.fromstring(z.read("modelDescription.xml"))


def units_of(md):
    """{unit name: {base unit exponent: value}}."""
    out = {}
    for unit in md.find("UnitDefinitions"):
        base = unit.find("BaseUnit")
        out[unit.get("name")] = {k: float(v) for k, v in (base.attrib.items() if base is not None else [])}
    return out


def real_units(md):
    """{variable name: its unit, its own or its declared type's} for every real variable."""
    if md.get("fmiVersion") == "2.0":
        types = {t.get("name"): t.find("Real") for t in md.find("TypeDefinitions")}
        found = {}
        for v in md.find("ModelVariables"):
            real = v.find("Real")
            if real is not None:
                declared = types.get(real.get("declaredType"))
                found[v.get("name")] = real.get("unit") or (declared.get("unit") if declared is not None else None)
        return found
    types = {t.get("name"): t for t in md.find("TypeDefinitions")}
    return {v.get("name"): v.get("unit") or (types[v.get("declaredType")].get("unit") if v.get("declaredType")
                                             else None)
            for v in md.find("ModelVariables") if v.tag == "Float64" and not v.get("name").startswith("indicator_")}


@pytest.fixture(params=["fmi2", "fmi3"])
def fmu(request, fmu_path, fmu3_path):
    return fmu_path if request.param == "fmi2" else fmu3_path


def test_every_real_variable_has_a_defined_unit_angles_in_radians(fmu):
    md = description(fmu)
    units = units_of(md)
    assert "1" not in units                                  # was the only unit, on everything
    assert units["rad"] == {"rad": 1.0}                      # the SI base unit of plane angle
    assert units[DIMENSIONLESS] == {}                        # no base unit exponent: a pure number
    found = real_units(md)
    assert {"theta", "phi", "y", "w", "epsilon", "energy"} <= set(found)
    for name, unit in found.items():
        assert unit in units, f"{name}: unit {unit!r} not in UnitDefinitions"
        if name in ANGLES or name in ANGULAR_RATES:
            assert units[unit] == {"rad": 1.0}, name
        elif name in ("x", "v", "y", "w", "F_N", "F_T", "energy", "alpha", "mu", "delta", "epsilon"):
            assert unit == DIMENSIONLESS, name


def test_the_default_experiment_has_a_step_size_that_fmpy_uses_as_its_output_interval(fmu):
    experiment = description(fmu).find("DefaultExperiment")
    stop, step = float(experiment.get("stopTime")), float(experiment.get("stepSize"))
    assert 0 < step <= stop / 100
    r = fmpy.simulate_fmu(fmu, output=["y"])                 # no output_interval: the stepSize's grid
    assert len(r) == pytest.approx(stop / step + 1, abs=2)


class _Table(html.parser.HTMLParser):
    """The rows of the page's tables, as lists of cell texts."""

    def __init__(self):
        super().__init__()
        self.rows, self._cell = [], None

    def handle_starttag(self, tag, attrs):
        if tag == "tr":
            self.rows.append([])
        elif tag in ("td", "th"):
            self._cell = ""

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self._cell is not None:
            self.rows[-1].append(self._cell)
            self._cell = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell += data


def test_the_documentation_lists_every_variable_with_its_unit_and_cites_the_paper(fmu, fmu_path):
    with zipfile.ZipFile(fmu) as z:
        page = z.read("documentation/index.html").decode()
    parser = _Table()
    parser.feed(page)
    header = next(r for r in parser.rows if r and r[0] == "name")
    rows = {r[0]: dict(zip(header, r)) for r in parser.rows if len(r) == len(header) and r[0] != "name"}
    md2 = description(fmu_path)                               # the variables' one home
    for v in md2.find("ModelVariables"):
        assert v.get("name") in rows, v.get("name")
        assert rows[v.get("name")]["causality"] == (v.get("causality") or "local")
    for name, unit in real_units(md2).items():
        assert rows[name]["unit"] == unit, name
    assert "On the regularization of impact without collision: the Painlev\u00e9 paradox and compliance" in \
        html.unescape(page)
