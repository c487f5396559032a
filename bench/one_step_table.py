# SPDX-License-Identifier: BSD-2-Clause
"""What the one-doStep-per-case tables (si_table.py, arm_table.py) share: a run timed from
fmi2Reset to its last read, and a table row from the repeated runs of a tolerance's cases."""
import statistics
import time

from painleve.fmu.cs_calls import initialize

REPEATS = 11


def header(error_label):
    return [f"| eps | rtol | {error_label} | us/case (slowest case) | fixed us/run | switches |",
            "|---|---|---|---|---|---|"]


def timed_run(ex, values, rtol, stop, read, step=True):
    """(seconds, read(instance, vr), switches) of one run on ex's instance: fmi2Reset, setup
    with the tolerance, `values` set, initialization, one fmi2DoStep from 0 to `stop` (none
    without `step`: the fixed cost), the reads."""
    vr, fmu = ex.vr, ex.instance
    t0 = time.perf_counter()
    fmu.reset()
    initialize(fmu, vr, values, rtol)
    if step:
        fmu.doStep(0.0, stop)
    out = read(fmu, vr)
    switches = fmu.getInteger([vr["switches"]])[0]
    return time.perf_counter() - t0, out, switches


def row(eps, rtol, label, cases):
    """The row of (eps, rtol): cases are (run, error) pairs, run(step) a timed_run of the case
    and error(outcome) its error against the reference; medians over REPEATS runs."""
    walls, fixed, errs, switches = [], [], [], []
    for run, error in cases:
        runs = [run(True) for _ in range(REPEATS)]
        walls.append(statistics.median(r[0] for r in runs))
        fixed.append(statistics.median(run(False)[0] for _ in range(REPEATS)))
        errs.append(error(runs[0][1]))
        switches.append(runs[0][2])
    return (f"| {eps:.0e} | {rtol:.0e} ({label}) | {max(errs):.1e} | {1e6 * statistics.median(walls):.0f} "
            f"({1e6 * max(walls):.0f}) | {1e6 * statistics.median(fixed):.0f} | {statistics.median(switches):.0f} |")
