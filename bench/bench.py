# SPDX-License-Identifier: BSD-2-Clause
"""What an IWC case costs, and how the cost grows as eps -> 0: every way we have
of running one, side by side in one process run, interleaved.

    .venv/bin/python bench/bench.py                # the full table -> docs/benchmarks.md
    .venv/bin/python bench/bench.py --quick        # fewer repeats, no sweep (a smoke run)

Runners (each on the same cases, at eps = 1e-2 ... 1e-6):
  fmpy ME simulate_fmu  fmpy.simulate_fmu(CVode) from the .fmu, one call per case
  fmpy ME fast loop     painleve Experiment: fmpy's CVode from event to event
                        (painleve.fmu.me_fast_loop), one instance, fmi2Reset between cases
  fmpy ME Euler         the fast loop under fmpy's Euler, h = eps/100
  fmpy CS simulate_fmu  fmpy.simulate_fmu(CoSimulation), one call per case
  fmpy CS fast loop     painleve Experiment(fmi_type="CoSimulation"): one long fmi2DoStep past the
                        lift-off, the outcome from the FMU's record (4 eps apart where it cannot tell)
  scipy <method>        painleve.experiments.reference (solve_ivp, the same model in Python)
  native                bench/native: the FMU's .so under CVODE in C, no Python

All run at the harness's tolerance, rtol = min(1e-6, eps/100), atol = rtol *
nominal (y ~ eps^2, w ~ eps). Wall time per case is the median over repeats;
the error is against the analytic e (the model's own O(eps ln 1/eps)) and
against the tightest run (scipy DOP853 at rtol 1e-12, an independent code).
Then the runners with a tolerance run again, each at the loosest rtol that
brings every case within 1 % of the model's own error of the tightest run:
the comparison at equal accuracy. RHS evaluations are counted where the
runner lets us: the ME fast loop, the scipy reference and the native driver
count their own, fmpy's Euler is counted by wrapping fmi2GetDerivatives;
fmpy's Co-Simulation hides the FMU's CVODE. Peak memory is each runner's process high-water mark (a
child process per runner, same cases once).

This file: the measurement, the rtols at equal accuracy, peak memory, the report;
the cases and the runners are in bench_runners.py.
"""
import argparse
import math
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

# bench_runners first: it keeps BLAS to one thread before numpy is imported.
from bench_runners import (EPSILONS, FMU, NATIVE, NATIVE_CS_FMUS, ROOT, SCIPY, TUNABLE, Runners,  # noqa: E402
                           an, cases_at, reference, run_native, w_error)
from cs_table import cs_markdown, cs_results  # noqa: E402
from si_table import si_markdown  # noqa: E402
import numpy as np                                       # noqa: E402


def measure(runners, names, repeats, epsilons, rtols=None):
    """rows[(runner, eps)] = list over cases of dict(seconds=[...], w, counters).
    Each repeat runs each runner over each eps's cases as one block, runners in an
    order rotated every repeat: every runner is timed warm (as the native driver,
    one process per block, always is) and all share the machine's drift.
    rtols[(runner, eps)]: the runner's rtol there (absent: the harness's)."""
    rtols = rtols or {}
    rows = {(n, eps): [dict(seconds=[]) for _ in cases_at(eps)] for n in names for eps in epsilons}
    for rep in range(repeats):
        order = names[rep % len(names):] + names[:rep % len(names)]
        for eps in epsilons:
            cases = cases_at(eps)
            for name in order:
                for i, (seconds, out) in enumerate(runners.run_block(name, cases, rtols.get((name, eps)))):
                    rows[name, eps][i]["seconds"].append(seconds)
                    rows[name, eps][i].update(out)
        print(f"repeat {rep + 1}/{repeats} done", file=sys.stderr)
    return rows


# Equal accuracy: each runner at the loosest rtol on this ladder that brings every
# case's w within TARGET_SHARE of the model's own error (the theorem's o(1)) of the
# tightest reference: accurate enough that what is measured is the model, no more.
LADDER = tuple(10 ** (-k / 2) for k in range(6, 23))    # 1e-3 ... 1e-11
TARGET_SHARE = 0.01


def accuracy_targets(ref, epsilons):
    """target[eps]: TARGET_SHARE of the largest |w/v0 - e| over the IWC cases (tight reference)."""
    return {eps: TARGET_SHARE * max(abs(w_error(c, w)) for c, w in zip(cases_at(eps), ref[eps]) if an.predict(c).iwc)
            for eps in epsilons}


def max_error(runners, name, eps, rtol, ref):
    """The largest |w - w_ref| over the cases at eps, the runner at rtol."""
    ws = [out["w"] for _, out in runners.run_block(name, cases_at(eps), rtol)]
    return max(abs(w - r) for w, r in zip(ws, ref[eps]))


def equal_accuracy_rtols(runners, ref, targets, names=TUNABLE):
    """chosen[(runner, eps)] = (rtol, error): the loosest rung meeting the target (absent if none does)."""
    chosen = {}
    for name in names:
        for eps, target in targets.items():
            for rtol in LADDER:
                err = max_error(runners, name, eps, rtol, ref)
                if err <= target:
                    chosen[name, eps] = (rtol, err)
                    break
    return chosen


def tightest(epsilons):
    return {eps: [reference.run_reference(c, method="DOP853", relative_tolerance=1e-12).w for c in cases_at(eps)]
            for eps in epsilons}


def peak_memory(names, epsilons):
    """Each runner's peak RSS (MiB) in a fresh child process running every case once."""
    peaks = {}
    for name in names:
        if name in NATIVE_CS_FMUS:
            continue
        if name == "native":
            rows = run_native(NATIVE, FMU, [c for eps in epsilons for c in cases_at(eps)])
            peaks[name] = f"{rows[0]['peak_rss_kib'] / 1024:.1f}"
            continue
        code = (f"import sys, resource; sys.argv = ['bench']; sys.path.insert(0, {str(HERE)!r}); import bench; "
                "rss = lambda: resource.getrusage(resource.RUSAGE_SELF).ru_maxrss; "
                f"r = bench.Runners(); base = rss(); "
                f"[r.run({name!r}, c) for e in {tuple(epsilons)!r} for c in bench.cases_at(e)]; print(base, rss())")
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
        base, peak = (int(x) / 1024 for x in out.stdout.split()[-2:])
        peaks[name] = f"{base:.0f} -> {peak:.0f}"
    return peaks


def growth(per_eps):
    """Fitted exponent p of count ~ (ln 1/eps)^p over the eps given (NaN without counts)."""
    eps = [e for e, v in per_eps.items() if v is not None and v > 0]
    if len(eps) < 2:
        return math.nan
    x, y = np.log([math.log(1 / e) for e in eps]), np.log([per_eps[e] for e in eps])
    return float(np.polyfit(x, y, 1)[0])


def summarize(names, rows, ref, epsilons):
    table = []
    for name in names:
        for eps in epsilons:
            cs = rows[name, eps]
            cases = cases_at(eps)
            median = lambda key: (statistics.median(c[key] for c in cs) if all(key in c for c in cs) else None)  # noqa
            table.append(dict(
                runner=name, eps=eps,
                ms=1e3 * statistics.median(statistics.median(c["seconds"]) for c in cs),
                nfev=median("nfev"), nsteps=median("nsteps"), nevents=median("nevents"),
                err_e=max(abs(w_error(k, c["w"])) for c, k in zip(cs, cases) if an.predict(k).iwc),
                err_ref=max(abs(c["w"] - r) for c, r in zip(cs, ref[eps]))))
    return table


def fmt(x, spec):
    return "–" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


def markdown(table, equal, chosen, targets, peaks, names, epsilons, sweep, command, seconds, cs_lines=()):
    out = [f"# Benchmarks: cost per IWC case", "",
           f"Command: `{command}` ({seconds:.0f} s). Machine: {platform.node()}, {platform.machine()}, "
           f"{os.cpu_count()} cores, {platform.platform()}, Python {platform.python_version()}, "
           f"load average at start {os.getloadavg()[0]:.2f}.", "",
           "Cases per eps: Theorem 1 at (theta0, delta) = (1, 1), (0.9, 0), (1.1, 0.5) and Theorem 2 "
           "(the video's rod) at w10 = 1.2 and 0.8 w1*; alpha = mu = 3. Each repeat runs each runner over "
           "each eps's five cases in a row (runners in an order rotated every repeat), so every runner is "
           "timed warm, as the native driver in its own process is. `ms` the median over cases of the median "
           "wall time over repeats; `nfev`, `steps`, `events` medians over cases; `|w/v0-e|` the largest over "
           "the IWC cases (the model's O(eps ln 1/eps)); `|w-w_ref|` the largest against scipy DOP853 at "
           "rtol 1e-12.", "",
           "## At the harness's tolerance", "",
           "rtol = min(1e-6, eps/100) for every solver but Euler (h = eps/100).", "",
           "| runner | eps | ms/case | nfev | steps | events | abs(w/v0-e) | abs(w-w_ref) |",
           "|---|---|---|---|---|---|---|---|"]
    for r in table:
        out.append(f"| {r['runner']} | {r['eps']:.0e} | {r['ms']:.3f} | {fmt(r['nfev'], '.0f')} | "
                   f"{fmt(r['nsteps'], '.0f')} | {fmt(r['nevents'], '.0f')} | {r['err_e']:.2e} | {r['err_ref']:.2e} |")
    out += ["", "## Growth as eps -> 0 and peak memory", "",
            "p: the fitted exponent of count ~ (ln 1/eps)^p from eps = 1e-2 to 1e-6 (p <= 1: no faster than "
            "ln 1/eps). Peak RSS: the runner's own process running every case once, after its imports and "
            "instances (Python: three FMU instances, fmpy, scipy) -> at its end; the native "
            "driver's whole process.", "",
            "| runner | p (nfev) | p (steps) | ms at 1e-2 -> 1e-6 | peak RSS MiB |", "|---|---|---|---|---|"]
    by = {(r["runner"], r["eps"]): r for r in table}
    for name in names:
        p_f = growth({e: by[name, e]["nfev"] for e in epsilons})
        p_s = growth({e: by[name, e]["nsteps"] for e in epsilons})
        out.append(f"| {name} | {fmt(p_f, '.2f')} | {fmt(p_s, '.2f')} | {by[name, epsilons[0]]['ms']:.3f} -> "
                   f"{by[name, epsilons[-1]]['ms']:.3f} | {peaks.get(name, '–')} |")
    out += ["", "## At equal accuracy", "",
            f"Each runner at the loosest rtol of 1e-3, 3e-4, ..., 1e-11 whose largest |w - w_ref| over the cases "
            f"is at most the target, {TARGET_SHARE:g} of the model's own error at that eps (the largest "
            "|w/v0 - e| of the tight reference): the solver's error is then negligible beside what is "
            "measured, and no runner is held to more.", "",
            "| runner | eps | target | rtol | abs(w-w_ref) | ms/case | nfev | steps |", "|---|---|---|---|---|---|---|---|"]
    eq = {(r["runner"], r["eps"]): r for r in equal}
    for name in TUNABLE:
        for eps in epsilons:
            if (name, eps) not in chosen:
                out.append(f"| {name} | {eps:.0e} | {targets[eps]:.1e} | not reached at 1e-11 | | | | |")
                continue
            r = eq[name, eps]
            out.append(f"| {name} | {eps:.0e} | {targets[eps]:.1e} | {chosen[name, eps][0]:.0e} | "
                       f"{r['err_ref']:.1e} | {r['ms']:.3f} | {fmt(r['nfev'], '.0f')} | {fmt(r['nsteps'], '.0f')} |")
    out += ["", "## Ratios at equal accuracy (ms/case)", "",
            "| eps | fastest scipy | ME fast loop / fastest scipy | fastest scipy / CS fast loop | "
            "CS fast loop / native |", "|---|---|---|---|---|"]
    for eps in epsilons:
        ms = {name: eq[name, eps]["ms"] if (name, eps) in chosen else math.nan for name in TUNABLE}
        sci = min((f"scipy {m}" for m in SCIPY), key=lambda n: ms[n] if not math.isnan(ms[n]) else math.inf)
        me, cs, nat = ms["fmpy ME fast loop"], ms["fmpy CS fast loop"], ms["native"]
        out.append(f"| {eps:.0e} | {sci} {ms[sci]:.3f} | {me / ms[sci]:.2f} | {ms[sci] / cs:.1f} | {cs / nat:.2f} |")
    if cs_lines:
        out += [""] + list(cs_lines)
    if sweep:
        out += ["", "## Sweep (in this process, or on dask when that is sooner)", ""] + sweep
    return "\n".join(out) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--quick", action="store_true", help="2 repeats, eps 1e-2 and 1e-4, no memory, no sweep")
    parser.add_argument("--sweep-cases", type=int, default=10_000)
    parser.add_argument("--out", default=str(ROOT / "docs" / "benchmarks.md"))
    args = parser.parse_args(argv)
    for path, how in ((FMU, "bash run.sh test (or cmake --build build)"), (NATIVE, "cmake --build build")):
        if not path.exists():
            sys.exit(f"{path} is missing: {how} builds it")
    start = time.monotonic()
    epsilons = (1e-2, 1e-4) if args.quick else EPSILONS
    repeats = 2 if args.quick else args.repeats
    ref = tightest(epsilons)
    runners = Runners()
    names = runners.names()
    table = summarize(names, measure(runners, names, repeats, epsilons), ref, epsilons)
    targets = accuracy_targets(ref, epsilons)
    chosen = equal_accuracy_rtols(runners, ref, targets)
    rtols = {key: rtol for key, (rtol, _) in chosen.items()}
    equal = summarize(TUNABLE, measure(runners, TUNABLE, repeats, epsilons, rtols), ref, epsilons)
    runners.close()
    from arm_table import arm_equal_markdown, arm_markdown
    from limit_compare import limit_markdown
    from tolerance_table import tolerance_markdown
    cs = cs_markdown(cs_results(ref, epsilons, LADDER)) + [""] + si_markdown(epsilons) + [""] + arm_markdown(epsilons)
    cs += [""] + limit_markdown(epsilons) + [""] + tolerance_markdown() + [""] + arm_equal_markdown(epsilons)
    peaks = {} if args.quick else peak_memory(names, epsilons)
    sweep = [] if args.quick else sweep_rows(args.sweep_cases)
    command = "python bench/bench.py" + (" " + " ".join(sys.argv[1:]) if len(sys.argv) > 1 else "")
    text = markdown(table, equal, chosen, targets, peaks, names, epsilons, sweep, command, time.monotonic() - start,
                    cs)
    print(text)
    if not args.quick:
        pathlib.Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        pathlib.Path(args.out).write_text(text)
        print(f"written to {args.out}", file=sys.stderr)


def sweep_rows(n):
    from sweep_bench import sweep_table
    return sweep_table(FMU, n)


if __name__ == "__main__":
    main()
