# SPDX-License-Identifier: BSD-2-Clause
"""The FMI 3.0 model description of a model (PainleveRod, PainleveRodSI, ShakerTable),
made from its FMI 2.0 one (the variables', units', experiment's and dependencies' one
home) at build time, and the FMI 3.0 source FMU's buildDescription.xml.

    python3 fmi3_model_description.py FMI2_XML OUT_DIR SOURCE...

FMI 3.0 names variables by type (Float64, Int32, Boolean), refers to them by
value reference where FMI 2.0 used indices, and makes the event indicators
and the independent variable `time` variables: they follow the model's own
value references (fmu_src/fmi/fmi3_instance.h).
"""
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

TYPES = {"Real": "Float64", "Integer": "Int32", "Boolean": "Boolean"}
# The event indicators of fmu_src/rod/rod.c, in order, as FMI 3.0 variables: (name,
# description, the knowns it depends on).
INDICATORS = [
    ("indicator_y", "y: the contact surface", "y"),
    ("indicator_g", "g = -y/eps - delta w: the compliant force's zero", "y w"),
    ("indicator_slip", "v while slipping; a + q_+ F_N (forward fold) while sticking", "v y w theta phi"),
    ("indicator_aux", "a + q_- F_N (backward fold) while sticking; w in flight", "y w theta phi"),
]
# PainleveRodSI's are rod.c's on the scaled state in the floor's frame (fmu_src/models/PainleveRodSI/rod_si.c):
# the floor's inputs enter with the states they offset, the applied loads with the sticking folds' a.
SI_INDICATORS = [
    ("indicator_y", "(y - the floor's height)/l: the contact surface", "y y_floor"),
    ("indicator_g", "the compliant force's zero in the paper's units: -gap/(eps l) - delta (w - w_floor)/sqrt(g l)",
     "y w y_floor w_floor"),
    ("indicator_slip", "(v - v_floor)/sqrt(g l) while slipping; a + q_+ F_N/(m g) (forward fold) while sticking",
     "v y w theta phi y_floor w_floor v_floor F_x F_y tau"),
    ("indicator_aux", "a + q_- F_N/(m g) (backward fold) while sticking; (w - w_floor)/sqrt(g l) in flight",
     "y w theta phi y_floor w_floor F_x F_y tau"),
]
# TwoLinkArm's are the contact core's over the arm (fmu_src/models/TwoLinkArm): the tip's gap and velocity are
# functions of the angles and rates, so each indicator depends on them.
ARM_STATES = "theta1 theta2 omega1 omega2"
ARM_INDICATORS = [
    ("indicator_y", "y/L: the tip's gap, the contact surface", "theta1 theta2"),
    ("indicator_g", "the compliant force's zero in the scaled units: -y/(eps L) - delta w/sqrt(g L)", ARM_STATES),
    ("indicator_slip", "v/sqrt(g L) while slipping; a + q_+ F_N/(M g) (forward fold) while sticking", ARM_STATES),
    ("indicator_aux", "a + q_- F_N/(M g) (backward fold) while sticking; w/sqrt(g L) in flight", ARM_STATES),
]
# Each model's event indicators and independent variable (its unit is one of the model's units).
MODELS = {
    "PainleveRod": (INDICATORS, "the paper's dimensionless time", "dimensionless"),
    "PainleveRodSI": (SI_INDICATORS, "time", "s"),
    "ShakerTable": ([], "time", "s"),
    "TwoLinkArm": (ARM_INDICATORS, "time", "s"),
}


def convert(md2):
    variables = md2.find("ModelVariables").findall("ScalarVariable")
    vr_of_index = {i + 1: v.get("valueReference") for i, v in enumerate(variables)}
    vr_of_name = {v.get("name"): v.get("valueReference") for v in variables}
    me2, cs2 = md2.find("ModelExchange"), md2.find("CoSimulation")
    indicators, time_description, time_unit = MODELS[md2.get("modelName")]
    assert len(indicators) == int(md2.get("numberOfEventIndicators", "0")), "one FMI 3.0 variable per indicator"
    derivatives = me2.get("providesDirectionalDerivative", "false")   # the FMI 2.0 flag: both kinds or neither

    root = ET.Element("fmiModelDescription", {
        "fmiVersion": "3.0", "modelName": md2.get("modelName"), "instantiationToken": md2.get("guid"),
        "description": md2.get("description"), "version": md2.get("version"),
        "generationTool": md2.get("generationTool"), "variableNamingConvention": "structured"})
    common = {"modelIdentifier": me2.get("modelIdentifier"), "needsExecutionTool": "false",
              "canBeInstantiatedOnlyOncePerProcess": "false", "canGetAndSetFMUState": "true",
              "canSerializeFMUState": "true", "providesDirectionalDerivatives": derivatives,
              "providesAdjointDerivatives": "true", "providesPerElementDependencies": "false"}
    ET.SubElement(root, "ModelExchange", {**common, "needsCompletedIntegratorStep": "false"})
    if cs2 is not None:
        ET.SubElement(root, "CoSimulation", {
            **common, "canHandleVariableCommunicationStepSize": "true", "maxOutputDerivativeOrder": "0",
            "providesIntermediateUpdate": "false", "mightReturnEarlyFromDoStep": "true",
            "canReturnEarlyAfterIntermediateUpdate": "false", "hasEventMode": "true"})

    # Units as FMI 2.0 has them (Unit, BaseUnit: the same elements and attributes in FMI 3.0).
    units2 = md2.find("UnitDefinitions")
    if units2 is not None:
        units = ET.SubElement(root, "UnitDefinitions")
        for unit in units2.findall("Unit"):
            u = ET.SubElement(units, "Unit", {"name": unit.get("name")})
            base = unit.find("BaseUnit")
            if base is not None:
                ET.SubElement(u, "BaseUnit", dict(base.attrib))
    if md2.find("TypeDefinitions") is not None:
        types = ET.SubElement(root, "TypeDefinitions")
        for simple in md2.find("TypeDefinitions"):
            real = simple.find("Real")
            ET.SubElement(types, "Float64Type", {"name": simple.get("name"), "description": simple.get("description"),
                                                 **{k: real.get(k) for k in ("quantity", "unit") if real.get(k)}})
    categories = ET.SubElement(root, "LogCategories")
    for category in md2.find("LogCategories"):
        ET.SubElement(categories, "Category", dict(category.attrib))
    ET.SubElement(root, "DefaultExperiment", dict(md2.find("DefaultExperiment").attrib))

    out = ET.SubElement(root, "ModelVariables")
    for v in variables:
        typed = next(iter(v))
        attrib = {k: v.get(k) for k in ("name", "valueReference", "description", "causality", "variability", "initial")
                  if v.get(k) is not None}
        for k in ("declaredType", "quantity", "unit", "start", "min", "max", "nominal"):
            if typed.get(k) is not None:
                attrib[k] = typed.get(k)
        if typed.get("derivative"):
            attrib["derivative"] = vr_of_index[int(typed.get("derivative"))]
        ET.SubElement(out, TYPES[typed.tag], attrib)
    first = 1 + max(int(v.get("valueReference")) for v in variables)
    ET.SubElement(out, "Float64", {"name": "time", "valueReference": str(first + len(indicators)),
                                   "causality": "independent", "variability": "continuous",
                                   "description": time_description, "quantity": "Time", "unit": time_unit})
    for k, (name, description, _) in enumerate(indicators):
        ET.SubElement(out, "Float64", {"name": name, "valueReference": str(first + k), "description": description,
                                       "causality": "local", "variability": "continuous"})

    structure = ET.SubElement(root, "ModelStructure")
    structure2 = md2.find("ModelStructure")
    for tag2, tag3 in (("Outputs", "Output"), ("Derivatives", "ContinuousStateDerivative"),
                       ("InitialUnknowns", "InitialUnknown")):
        for unknown in structure2.find(tag2):
            dependencies = " ".join(vr_of_index[int(i)] for i in unknown.get("dependencies").split())
            ET.SubElement(structure, tag3, {"valueReference": vr_of_index[int(unknown.get("index"))],
                                            "dependencies": dependencies})
    for k, (_, _, names) in enumerate(indicators):
        ET.SubElement(structure, "EventIndicator", {
            "valueReference": str(first + k), "dependencies": " ".join(vr_of_name[n] for n in names.split())})
    return root


def build_description(model_identifier, sources):
    root = ET.Element("fmiBuildDescription", {"fmiVersion": "3.0"})
    configuration = ET.SubElement(root, "BuildConfiguration", {"modelIdentifier": model_identifier})
    files = ET.SubElement(configuration, "SourceFileSet", {"language": "C99"})
    for source in sources:
        ET.SubElement(files, "SourceFile", {"name": source})
    return root


def write(root, path):
    ET.indent(root)
    ET.ElementTree(root).write(path, encoding="UTF-8", xml_declaration=True)


def main():
    fmi2, out_dir, sources = Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3:]
    md3 = convert(ET.parse(fmi2).getroot())
    out_dir.mkdir(parents=True, exist_ok=True)
    write(md3, out_dir / "modelDescription.xml")
    write(build_description(md3.find("ModelExchange").get("modelIdentifier"), sources),
          out_dir / "buildDescription.xml")


if __name__ == "__main__":
    main()
