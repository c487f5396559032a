# SPDX-License-Identifier: BSD-2-Clause
"""The FMU's documentation/index.html, made at build time from the FMI 2.0 model
description (the variables', units' and experiment's one home), so that the page
and the model cannot disagree. Both FMUs (FMI 2.0 and 3.0) carry it.

    python3 fmu_documentation.py MODEL_DESCRIPTION_XML OUT_DIR [LICENSES_DIR]

LICENSES_DIR: the folder the FMU carries as documentation/licenses/ (cmake/fmu_licenses.py),
whose files the page links, its license.txt first.
"""
import html
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

CITATION = ("S. J. Hogan and K. Uldall Kristiansen, \"On the regularization of impact without collision: "
            "the Painlev\u00e9 paradox and compliance\", Proceedings of the Royal Society A 473 (2017) 20160773, "
            "doi:10.1098/rspa.2016.0773 (arXiv:1610.00143)")


def children(md, tag):
    element = md.find(tag)
    return list(element) if element is not None else []


def variable_rows(md):
    """(name, causality, variability, type, unit, start, min, max, description) of each variable."""
    types = {t.get("name"): t.find("Real") for t in children(md, "TypeDefinitions")}
    variables = md.find("ModelVariables").findall("ScalarVariable")
    for v in variables:
        typed = next(iter(v))
        declared = types.get(typed.get("declaredType"))

        def attr(name):
            value = typed.get(name)
            return value if value is not None or declared is None else declared.get(name)
        description = v.get("description") or ""
        if typed.get("derivative"):
            description = f"derivative of {variables[int(typed.get('derivative')) - 1].get('name')}" + \
                          (f"; {description}" if description else "")
        yield (v.get("name"), v.get("causality") or "local", v.get("variability") or "continuous", typed.tag,
               attr("unit") or "", typed.get("start") or "", attr("min") or "", attr("max") or "", description)


def table(header, rows):
    cells = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "\n".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>" for row in rows)
    return f"<table>\n<tr>{cells}</tr>\n{body}\n</table>"


def licenses_section(licenses):
    """The licenses' links: license.txt (what each file covers) first, then the files."""
    if licenses is None:
        return ""
    names = ["license.txt"] + sorted(p.name for p in licenses.iterdir() if p.name != "license.txt")
    items = "\n".join(f'<li><a href="licenses/{html.escape(n)}">{html.escape(n)}</a></li>' for n in names)
    return ("<h2>Licenses</h2>\n<p>The FMU is BSD-2-Clause licensed; it contains SUNDIALS CVODE (BSD-3-Clause) "
            "and is compiled with the FMI headers (BSD-2-Clause). license.txt says which file covers what, "
            f"and which versions:</p>\n<ul>\n{items}\n</ul>\n")


def page(md, licenses=None):
    units = []
    for unit in children(md, "UnitDefinitions"):
        base = unit.find("BaseUnit")
        exponents = " ".join(f"{k}^{v}" for k, v in (base.attrib.items() if base is not None else []))
        units.append((unit.get("name"), exponents or "none (dimensionless)"))
    experiment = md.find("DefaultExperiment")
    interfaces = [tag for tag in ("ModelExchange", "CoSimulation") if md.find(tag) is not None]
    title = f"{md.get('modelName')} {md.get('version') or ''}".strip()
    # The rod's models cite the paper (in any units); another model (ShakerTable) is only itself.
    rod = (md.get("modelName") or "").startswith("PainleveRod")
    citation = f"<p>The model of {html.escape(CITATION)}.</p>\n" if rod else ""
    if any(name == "dimensionless" for name, _ in units):
        scales = ("<p>Dimensionless in the paper's scales: lengths in the half-length l, time in T = sqrt(l/g), "
                  "forces in m g;\nangles in radians.</p>")
    else:
        scales = "<p>SI units.</p>"
    doc = {"PainleveRod": "docs/model.md", "PainleveRodSI": "docs/si_model.md"}.get(md.get("modelName"))
    equations = f"; the repository's {doc} has the equations." if doc else "."
    return f"""<!DOCTYPE html>
<html lang="en">
<head><meta charset="utf-8"><title>{html.escape(title)}</title>
<style>body{{font-family:sans-serif;max-width:60em;margin:2em auto}}td,th{{border:1px solid #ccc;padding:2px 6px}}
table{{border-collapse:collapse}}</style></head>
<body>
<h1>{html.escape(title)}</h1>
<p>{html.escape(md.get('description') or '')}</p>
{citation}<p>Interfaces: {html.escape(', '.join(interfaces))}. Default experiment:
{html.escape(', '.join(f'{k} = {v}' for k, v in (experiment.attrib.items() if experiment is not None else [])))}.</p>
<h2>Units</h2>
{scales}
{table(("unit", "base unit exponents"), units)}
<h2>Variables</h2>
{table(("name", "causality", "variability", "type", "unit", "start", "min", "max", "description"),
       variable_rows(md))}
{licenses_section(licenses)}<p>Made from modelDescription.xml when the FMU was built{equations}</p>
</body>
</html>
"""


def main():
    md = ET.parse(sys.argv[1]).getroot()
    out = Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    licenses = Path(sys.argv[3]) if len(sys.argv) > 3 else None
    (out / "index.html").write_text(page(md, licenses), encoding="utf-8")


if __name__ == "__main__":
    main()
