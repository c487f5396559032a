# SPDX-License-Identifier: BSD-2-Clause
"""Benchmark of bounded calls: the random legal cases of tests/fmu/test_bounded_calls.py
(bench/bounded_cases.py), a few thousand by default, and a table per model x FMI
version x interface (Model Exchange per solver): cases, hangs, crashes, Zeno
errors, other errors, Discards, runs where fmpy's CVode gave up, and the slowest
single call (its time, the call, its case). The calls that once hung run first (negative
case numbers). Nothing is asserted: a report.

    python bench/bounded_calls.py [--cases N] [--seed S] [--wall SECONDS] [--show error discard]
    python bench/bounded_calls.py --seed S --only K [K...]    replay cases (their values and outcomes)
"""
import argparse
import collections
import pathlib
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import bounded_cases as bc  # noqa: E402
import bounded_runs as br  # noqa: E402

COLUMNS = ("hang", "crash", "zeno", "illegal", "harness", "t-limit", "error", "discard", "solver")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=3000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--wall", type=float, default=10.0, help="a case's wall limit, seconds (a hang past it)")
    parser.add_argument("--only", type=int, nargs="*", help="run just these cases (negative: the calls that once hung)")
    parser.add_argument("--no-regression-cases", action="store_true")
    parser.add_argument("--show", nargs="*", default=[], metavar="OUTCOME",
                        help="print the cases with these outcomes too (e.g. error discard); failures always")
    args = parser.parse_args(argv)
    models = bc.read_models()
    regression = {case["index"]: case for case in bc.regression_cases(models)}
    if args.only is not None:
        cases = [regression[k] if k < 0 else bc.make_case(models, args.seed, k) for k in args.only]
    else:
        cases = ([] if args.no_regression_cases else list(regression.values())) + \
                [bc.make_case(models, args.seed, k) for k in range(args.cases)]
    started = time.time()
    verbose = args.only is not None

    def progress(case, result):
        if verbose or result["outcome"] in br.FAILURES or result["outcome"] in args.show:
            print(f"{result['outcome'].upper()} {bc.describe(case)}\n    {result['detail'][:300]}"
                  f"\n    slowest call {result['slowest'][0]:.3f} s: {result['slowest'][1][:120]}", flush=True)

    results = br.run_cases(models, cases, args.wall, progress)
    print(f"\n{len(cases)} cases (seed {args.seed}, wall limit {args.wall:g} s) in {time.time() - started:.0f} s")
    print(table(cases, results))


def table(cases, results):
    rows = collections.defaultdict(lambda: dict(cases=0, slowest=(0.0, "", None), **{c: 0 for c in COLUMNS}))
    for case in cases:
        result = results[case["index"]]
        key = (case["model"], f"FMI {case['fmi']}.0",
               case["interface"] + (f" {case['solver']}" if case["interface"] == "ME" else ""))
        row = rows[key]
        row["cases"] += 1
        row[result["outcome"]] = row.get(result["outcome"], 0) + 1
        if result["slowest"][0] > row["slowest"][0]:
            row["slowest"] = (result["slowest"][0], result["slowest"][1], case["index"])
    head = (f"{'model':14} {'FMI':7} {'run':9} {'cases':>5} " + " ".join(f"{c:>7}" for c in COLUMNS)
            + "  slowest call (s, case, call)")
    lines = [head, "-" * len(head)]
    for key in sorted(rows):
        row = rows[key]
        seconds, call, index = row["slowest"]
        name = call.split("(", 1)[0]
        lines.append(f"{key[0]:14} {key[1]:7} {key[2]:9} {row['cases']:>5} "
                     + " ".join(f"{row[c]:>7}" for c in COLUMNS)
                     + f"  {seconds:8.3f}  {index if index is not None else '-':>5}  {name}")
    return "\n".join(lines)


if __name__ == "__main__":
    main()
