"""What the relative tolerance delivers: bench.py's 25 cases (eps = 1e-2 ... 1e-6, four IWC
cases and one direct lift-off per eps) through the FMU's Co-Simulation (one fmi2DoStep per
case from C, bench/native's painleve_native_cs) at rtol = 1e-4 ... 1e-10, the outcome at the
return to y = 0 against the tight reference (scipy's DOP853 at rtol 1e-12, the same model in
Python: an independent code).

    .venv/bin/python bench/tolerance_table.py [--fmu build/PainleveRod.fmu]

Per rtol, the largest error over the cases, divided by rtol: w relative (the IWC cases,
w of the order e v0), w relative (the lift-off, w of the order eps v0: the size of its
nominal) and w relative to |w| + eps v0 (the weight the error control puts on w, in units
of rtol: atol = rtol x nominal, nominal eps); phi and theta relative; v relative to v0 (v at
the return is O(eps) or less, below the reference's own resolution relative to itself)."""
import argparse
import os
import pathlib
import shutil
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from bench_runners import EPSILONS, FMU, an, cases_at  # noqa: E402
from limit_compare import run_fmu, tight_reference  # noqa: E402

TOLERANCES = tuple(10.0 ** -k for k in range(4, 11))
COLUMNS = ("w IWC rel.", "w lift-off rel.", "w / (abs(w) + eps v0)", "phi rel.", "theta rel.", "v / v0")


def errors(rows, cases, ref):
    """The largest error of each column over the cases (the case's kind from the theory's prediction)."""
    out = dict.fromkeys(COLUMNS, 0.0)
    for r, c, q in zip(rows, cases, ref):
        key = "w IWC rel." if an.predict(c).iwc else "w lift-off rel."
        dw = abs(r["w"] - q["w"])
        out[key] = max(out[key], dw / abs(q["w"]))
        out["w / (abs(w) + eps v0)"] = max(out["w / (abs(w) + eps v0)"], dw / (abs(q["w"]) + c.epsilon * c.v0))
        out["phi rel."] = max(out["phi rel."], abs(r["phi"] - q["phi"]) / abs(q["phi"]))
        out["theta rel."] = max(out["theta rel."], abs(r["theta"] - q["theta"]) / abs(q["theta"]))
        out["v / v0"] = max(out["v / v0"], abs(r["v"] - q["v"]) / c.v0)
    return out


def table(fmu_dir, epsilons=EPSILONS, tolerances=TOLERANCES):
    """{rtol: {column: largest error over every eps's cases}}."""
    setup = [(cases_at(eps), tight_reference(cases_at(eps))) for eps in epsilons]
    result = {}
    for tol in tolerances:
        worst = dict.fromkeys(COLUMNS, 0.0)
        for cases, ref in setup:
            for k, v in errors(run_fmu(fmu_dir, cases, tol, repeat=1), cases, ref).items():
                worst[k] = max(worst[k], v)
        result[tol] = worst
    return result


def markdown(result):
    lines = ["| rtol | " + " | ".join(f"{c} / rtol" for c in COLUMNS) + " |", "|---" * (1 + len(COLUMNS)) + "|"]
    for tol, worst in result.items():
        lines.append(f"| {tol:.0e} | " + " | ".join(f"{worst[c] / tol:.2f}" for c in COLUMNS) + " |")
    return lines


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fmu", type=pathlib.Path, default=FMU)
    args = parser.parse_args(argv)
    tmp = tempfile.mkdtemp(prefix="tolerance-table-")
    try:
        fmu_dir = args.fmu
        if str(fmu_dir).endswith(".fmu"):
            from fmpy import extract
            fmu_dir = extract(str(fmu_dir), os.path.join(tmp, "fmu"))
        print("\n".join(markdown(table(fmu_dir))))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
