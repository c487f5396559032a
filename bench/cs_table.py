# SPDX-License-Identifier: BSD-2-Clause
"""Co-Simulation from C: each IWC case through the FMU's own
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
    "Where the time of the explicit path goes (perf over 3,000 runs of each case at eps = 1e-6 and 1e-2, rtol "
    "1e-6): a quarter in sin and cos (one sincos a right-hand side: the body's evaluation computes them once "
    "and only eq coeffs' a and b), 35-39 % in the rod's body and the contact core's right-hand side "
    "(rod_evaluate, contact_derivatives: 6 evaluations a step, 30-64 steps a case at eps = 1e-2 ... 1e-6, "
    "186-390 evaluations), 11-14 % in the pair's own arithmetic (stages, error norm, dense output), 3 % in pow "
    "of the step control, 5-6 % in the event indicators after each step, the rest in the event updates "
    "(moving off the surfaces: the event log's text is no longer formatted while logEvents is off, 4-7 % "
    "before) and the fixed cost (reset, set values, initialization, reads). The flight is evaluated in "
    "closed form (fmu_src/fmi/closed_flight.c: 8-36 evaluations a case, samples and root finding, about 1-2 % "
    "of the time), so it carries the lift-off velocity to the horizon without integration error: at eps = "
    "1e-2 the default tolerance is now within 1e-6 (2.5e-7; the explicit pair's flight left 2.8e-5). Fewer "
    "evaluations in the contact need a higher order (an 8th-order pair takes about a third of the steps at 12 "
    "evaluations each). This run's machine was loaded (load average 3.5-6: other jobs on its 2 cores), and "
    "the times above scatter with it: main's build before the closed-form flight, run interleaved with this "
    "one (the fastest of 3 rounds of 20 repeats), took 40.8, 42.1, 45.7, 53.7, 53.5 us per case at eps = "
    "1e-2 ... 1e-6 (default tolerance) where this build took 25.4, 31.5, 29.9, 33.9, 35.5 (0.62-0.75x; the "
    "last quiet run of this table had main's at 20-29 us, so about 13-20 us here). A sustained contact (CVODE "
    "after the hand-over), interleaved the same way through fmpy: the rod put down at rest at theta = 1, eps = "
    "1e-6, one step of 0.01 (it sticks and tips over), 0.49 -> 0.38 ms; sliding at v = 1, theta = 0.3, "
    "mu = 0.3, eps = 1e-4 for 0.2, 0.32 -> 0.25 ms: no slower (the cheaper right-hand side)."
    " Side by side with the build before the flight on a quiet machine (bench/cs_compare.py, two runs on 2026-11-26 at load 0.8-1.0), this build takes 0.63-0.67 and 0.65-0.73 of its time per case at every eps; the same runs had the old build at 40-55 and 57-81 us, where the last session's quiet table had it at 20-29 us: the VM's speed drifts 2-3x between hours, so only side-by-side ratios compare, and scaled to that table this build takes 13-20 us per case (five times the single-purpose code's 3.9-6.4 us is 20-32 us).")


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
