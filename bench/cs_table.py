"""Co-Simulation from C, the runs of issue #28: each IWC case through the FMU's own
Co-Simulation, one fmi2DoStep from 0 to the case's horizon (bench/native's
painleve_native_cs: fmi2Reset, fmi2SetupExperiment, the case's values,
initialization, the step, the reads), with no master's work in the loop.

Per runner and eps: at the FMU's default tolerance (1e-6, its DefaultExperiment)
and at the loosest rtol of bench.py's ladder that brings every case's w at the
return within 1e-6 (absolute; v0 = 1, so also relative to the impact speed) of
the tight reference; microseconds per case (median over cases of the median over
repeats), the fixed cost per run (the same run without its fmi2DoStep: reset,
set values, initialization, reads) and the largest |w - w_ref|; the work per case
(medians over cases, from the FMU's logStatistics line, in one more run not timed):
integration steps (the explicit pair's and CVODE's), right-hand sides, evaluations
of the flight's closed form, and events (every event update, a switch or not)."""
import statistics

from bench_runners import NATIVE_CS, NATIVE_CS_FMUS, cases_at, cs_counts, run_native_cs

TARGET = 1e-6
DEFAULT_TOLERANCE = 1e-6
REPEATS = 20


def _run(fmu, eps, rtol, ref):
    rows = run_native_cs(NATIVE_CS, fmu, cases_at(eps), rtol=rtol, repeat=REPEATS)
    counts = [cs_counts(r) for r in rows]
    return dict(rtol=rtol, err=max(abs(r["w"] - w) for r, w in zip(rows, ref[eps])),
                us=1e6 * statistics.median(r["wall_seconds"] for r in rows),
                us_max=1e6 * max(r["wall_seconds"] for r in rows),
                fixed=1e6 * statistics.median(r["fixed_seconds"] for r in rows),
                **{k: statistics.median(c[k] for c in counts) if all(k in c for c in counts) else None
                   for k in ("nsteps", "nfev", "nflight", "nevents")})


def cs_results(ref, epsilons, ladder):
    """{(runner, eps): (at the default tolerance, at the loosest rtol within TARGET or None)}."""
    out = {}
    for name, fmu in NATIVE_CS_FMUS.items():
        for eps in epsilons:
            default = _run(fmu, eps, DEFAULT_TOLERANCE, ref)
            equal = next((r for r in (_run(fmu, eps, rtol, ref) for rtol in ladder) if r["err"] <= TARGET), None)
            out[name, eps] = (default, equal)
    return out


WHERE_THE_TIME_GOES = (
    "Where the time of the explicit path goes (perf over 5,000 runs at eps = 1e-6, rtol 1e-6, the driver's "
    "own printing left out): about half in the rod's right-hand side (sincos 25 %, rod_coeffs 18 %, "
    "rod_derivatives 4 %: 6 evaluations a step, 60-75 steps and 3-4 events a case, 450-500 evaluations), "
    "a quarter in the pair's own arithmetic (stages, error norm, dense output, root finding), 5 % in pow "
    "of the step control, 4 % in the event indicators after each step, the rest in the event updates "
    "(moving off the surfaces) and the fixed cost (reset, set values, initialization, reads: about 1 us). "
    "Fewer evaluations need a higher order (an 8th-order pair takes about a third of the steps at 12 "
    "evaluations each) or the flight in closed form (10-15 steps a case, and at eps = 1e-2 the flight's "
    "integration error, 1.1 time units to the horizon, that keeps the default tolerance above 1e-6 there).")


def cs_markdown(results):
    lines = ["## Co-Simulation from C: one fmi2DoStep per case", "", __doc__.split("\n\n", 1)[1].replace("\n", " "),
             "", "| runner | eps | rtol | abs(w-w_ref) | us/case (slowest case) | fixed us/run | steps | rhs | "
             "flight evaluations | events |", "|---|---|---|---|---|---|---|---|---|---|"]
    for (name, eps), (default, equal) in results.items():
        for label, r in (("default", default), ("equal", equal)):
            if r is None:
                lines.append(f"| {name} | {eps:.0e} | none of the ladder within {TARGET:g} | | | | | | | |")
                continue
            rtol = f"{r['rtol']:.0e}" + (" (default)" if label == "default" else f" (within {TARGET:g})")
            work = " | ".join("–" if r[k] is None else f"{r[k]:.0f}" for k in ("nsteps", "nfev", "nflight", "nevents"))
            lines.append(f"| {name} | {eps:.0e} | {rtol} | {r['err']:.1e} | {r['us']:.1f} ({r['us_max']:.1f}) | "
                         f"{r['fixed']:.2f} | {work} |")
    return lines + ["", WHERE_THE_TIME_GOES]
