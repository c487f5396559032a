# SPDX-License-Identifier: BSD-2-Clause
"""The checks of `validate` that need no theorem: fmpy's static validation,
the interface contract of docs/model.md §4, and the default experiment as any FMI
tool would run it."""
import math

import numpy as np

from .report import Check

# docs/model.md §4: name -> (causality, variability, type, start or None)
CONTRACT = {
    "alpha": ("parameter", "fixed", "Real", 3.0),
    "mu": ("parameter", "fixed", "Real", 3.0),
    "delta": ("parameter", "fixed", "Real", 1.0),
    "epsilon": ("parameter", "fixed", "Real", 1e-3),
    "x": ("output", "continuous", "Real", 0.0),
    "v": ("output", "continuous", "Real", 1.0),
    "y": ("output", "continuous", "Real", 0.0),
    "w": ("output", "continuous", "Real", 0.0),
    "theta": ("output", "continuous", "Real", 1.0),
    "phi": ("output", "continuous", "Real", 0.5),
    "F_N": ("output", "continuous", "Real", None),
    "F_T": ("output", "continuous", "Real", None),
    "mode": ("output", "discrete", "Integer", None),
    "contact": ("output", "discrete", "Boolean", None),
}
STATES = ("x", "v", "y", "w", "theta", "phi")
# FMI 3.0's names of the contract's types (the same variables in the FMI 3.0 FMU).
FMI3_TYPES = {"Real": "Float64", "Integer": "Int32", "Boolean": "Boolean"}


def contract_problems(md):
    problems = []
    if md.fmiVersion not in ("2.0", "3.0"):
        problems.append(f"fmiVersion is {md.fmiVersion}, not 2.0 or 3.0")
    type_name = (lambda t: FMI3_TYPES[t]) if md.fmiVersion == "3.0" else (lambda t: t)
    if md.modelExchange is None:
        problems.append("no ModelExchange element")
    for kind in (md.modelExchange, md.coSimulation):
        if kind is not None and kind.modelIdentifier != "PainleveRod":
            problems.append(f"modelIdentifier is {kind.modelIdentifier}, not PainleveRod")
    variables = {v.name: v for v in md.modelVariables}
    for name, (causality, variability, typ, start) in CONTRACT.items():
        typ = type_name(typ)
        v = variables.get(name)
        if v is None:
            problems.append(f"no variable {name}")
            continue
        if (v.causality, v.variability, v.type) != (causality, variability, typ):
            problems.append(f"{name} is {v.causality}/{v.variability}/{v.type}, not {causality}/{variability}/{typ}")
        if start is not None and (v.start is None or not math.isclose(float(v.start), start)):
            problems.append(f"{name} starts at {v.start}, not {start:g}")
    for name in STATES:
        if f"der({name})" not in variables:
            problems.append(f"no derivative der({name})")
    return problems


def static_checks(fmu_path):
    from fmpy import read_model_description
    from fmpy.validation import validate_fmu
    problems = validate_fmu(fmu_path)
    checks = [Check("static/fmpy", "fmpy static validation (archive, XML schema, names, ModelStructure)",
                    "no problems" if not problems else "; ".join(p.strip() for p in problems)[:400],
                    "no problems", not problems, dict(problems=problems))]
    if problems:
        return checks
    found = contract_problems(read_model_description(fmu_path))
    checks.append(Check("static/contract", "interface contract (docs/model.md §4: names, causality, variability, starts)",
                        "as specified" if not found else "; ".join(found), "as specified", not found,
                        dict(problems=found)))
    return checks


def default_experiment_check(fmu_path, interface):
    """The FMU opened with its defaults, as any tool would, must show an IWC:
    touch, stick, and leave the floor moving up before the stop time."""
    import tempfile

    from fmpy import extract, simulate_fmu
    cid = f"default/{interface}"
    what = f"default experiment through {'Model Exchange' if interface == 'ME' else 'Co-Simulation'} shows an IWC"
    said = []
    # Extracted here, not by fmpy (which leaves its copy behind when the run fails); the FMU's
    # messages go into the check, not to stdout, which --json keeps for the report.
    with tempfile.TemporaryDirectory(prefix="painleve-") as tmp:
        try:
            r = simulate_fmu(extract(fmu_path, tmp), fmi_type="ModelExchange" if interface == "ME" else "CoSimulation",
                             output=["y", "w", "mode", "contact"],
                             logger=lambda component, name, status, category, message: said.append(message))
        except Exception as err:
            first = said[0].decode(errors="replace") if said else ""
            return Check(cid, what, f"simulation failed: {first or err}", "runs", False)
    contact = r["contact"].astype(bool)
    stuck = bool(np.any(contact & (r["mode"] == 0)))
    y_end, w_end = float(r["y"][-1]), float(r["w"][-1])
    passed = bool(contact.any()) and stuck and y_end > 0 and w_end > 0
    return Check(cid, what, f"touched {bool(contact.any())}, stuck {stuck}, at t={r['time'][-1]:g}: "
                            f"y={y_end:.3g} w={w_end:.3g}", "touch, stick, then y > 0, w > 0", passed,
                 dict(touched=bool(contact.any()), stuck=stuck, y_end=y_end, w_end=w_end))
