# SPDX-License-Identifier: BSD-2-Clause
"""model_dependencies.h from a model description's <ModelStructure>: the one home of which
unknown depends on which known. A model whose partial derivatives come from a chain rule
(fmu_src/models/PainleveRodSI) answers exactly 0 for every pair not declared here, where the chain
rule would leave round-off; the conformance tests check the declared pairs against central
differences and the undeclared ones against zero.

    python3 model_dependencies.py MODEL_DESCRIPTION_XML OUT_HEADER
"""
import sys
import xml.etree.ElementTree as ET
from pathlib import Path


def pairs(md):
    variables = md.find("ModelVariables").findall("ScalarVariable")
    vr = {i + 1: int(v.get("valueReference")) for i, v in enumerate(variables)}
    found = set()
    for unknown in md.find("ModelStructure").iter("Unknown"):
        for known in (unknown.get("dependencies") or "").split():
            found.add((vr[int(unknown.get("index"))], vr[int(known)]))
    return len(variables), sorted(found)


def header(md):
    n, found = pairs(md)
    rows = "\n".join(f"    [{u}][{k}] = true," for u, k in found)
    return f"""/* Generated from modelDescription.xml's <ModelStructure> by cmake/model_dependencies.py: do not edit. */
#ifndef MODEL_DEPENDENCIES_H
#define MODEL_DEPENDENCIES_H

#include <stdbool.h>

/* DEPENDS[unknown][known]: declared in Outputs, Derivatives or InitialUnknowns (value references). */
static const bool MODEL_DEPENDS[{n}][{n}] = {{
{rows}
}};

static bool model_depends(unsigned int unknown, unsigned int known)
{{
    return unknown < {n} && known < {n} && MODEL_DEPENDS[unknown][known];
}}

#endif
"""


if __name__ == "__main__":
    md_path, out = sys.argv[1], Path(sys.argv[2])
    text = header(ET.parse(md_path).getroot())
    if not out.exists() or out.read_text() != text:
        out.write_text(text)
