# SPDX-License-Identifier: BSD-2-Clause
"""The differential test (tests/differential/test_differential.py) at any size, off CI: random legal
cases of every model, FMI 2.0 and 3.0, Co-Simulation at the default, a loose and a tight tolerance
and Model Exchange under fmpy's CVode, each against its independent reference
(tests/helpers/differential.py). Prints per model, version and setting the runs, the failures and
the worst difference (as a multiple of its bound), and per model the cases left out as near a
separatrix and the Model Exchange runs run again on a finer output grid.

    .venv/bin/python bench/differential.py --cases 3000 [--seed S] [--models TwoLinkArm ...]

--cases is per model. Exit status 1 if any run failed."""
import argparse
import collections
import pathlib
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from helpers import differential as D          # noqa: E402

SETTINGS = ("CS default", "CS loose", "CS tight", "ME")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=300, help="cases per model (default 300)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--models", nargs="+", default=list(D.MODELS), choices=D.MODELS)
    ap.add_argument("--show", type=int, default=3, help="failed runs shown per row (default 3)")
    args = ap.parse_args(argv)
    any_failed = False
    for model in args.models:
        t0 = time.perf_counter()
        plan = [(case, runs, D.sensitive(case)) for case, runs in D.plan(model, args.cases, args.seed)]
        left_out = sum(s for _, _, s in plan)
        extra = (f", {D.REDRAWN[model]} draws the reference could not compare (the arm: drawn again; the rods: "
                 f"compared at the return)") if model in D.REDRAWN else ""
        print(f"{model}: {len(plan)} cases, {left_out} left out{extra}; references {time.perf_counter() - t0:.1f} s",
              flush=True)
        for version in D.VERSIONS:
            loaded = D.Loaded(D.fmu_path(model, version))
            rows = collections.defaultdict(list)
            t1 = time.perf_counter()
            try:
                for case, runs, out in plan:
                    if out:
                        continue
                    for setting, (interface, tol, steps) in zip(SETTINGS, runs):
                        rows[setting].append(D.run_case(loaded, case, interface, tol, steps))
            finally:
                loaded.close()
            print(f"  FMI {version} ({time.perf_counter() - t1:.1f} s)")
            for setting in SETTINGS:
                outs = rows[setting]
                failed = [o for o in outs if o.failed]
                errors = sum(o.error is not None for o in failed)
                ratios = [o.diff / o.bound for o in outs if o.error is None]
                worst_diff = max((o.diff for o in outs if o.error is None), default=float("nan"))
                print(f"    {setting:10s} runs {len(outs):5d}  failed {len(failed):4d} (errors {errors:3d})  "
                      f"worst diff {worst_diff:.3g}  worst diff/bound {max(ratios, default=float('nan')):.3g}")
                for o in sorted(failed, key=lambda o: -(float("inf") if o.error else o.diff / o.bound))[:args.show]:
                    print(f"      {o!r}")
                any_failed |= bool(failed)
        print(f"  {D.REFINED[model]} Model Exchange runs hit fmpy's mxstep and were run on a 10 times finer grid")
    return 1 if any_failed else 0


if __name__ == "__main__":
    sys.exit(main())
