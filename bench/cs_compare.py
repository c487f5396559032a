# SPDX-License-Identifier: BSD-2-Clause
"""Two builds of PainleveRod.fmu side by side in one run: each benchmark case through one
fmi2DoStep from C (bench/native's painleve_native_cs, as cs_table.py) at the FMU's default
tolerance, the builds interleaved eps by eps for ROUNDS rounds (the fastest round kept), so
that both see the same machine: a 2-core VM whose speed drifts from day to day, which makes a
comparison with another day's table unfair.

    .venv/bin/python bench/cs_compare.py OLD.fmu NEW.fmu     # prints the markdown table

Per eps: us per case (median over cases of the median over 20 repeats; the slowest case in
brackets), the new build's fixed cost per run and |w - w_ref| of each (w_ref: DOP853 at 1e-12)."""
import os
import sys

from bench import EPSILONS, tightest
from cs_table import DEFAULT_TOLERANCE, _run

ROUNDS = 3


def compare(old, new, epsilons=EPSILONS):
    ref = tightest(epsilons)
    best = {}
    for _ in range(ROUNDS):
        for name, fmu in (("old", old), ("new", new)):
            for eps in epsilons:
                r = _run(fmu, eps, DEFAULT_TOLERANCE, ref)
                if (name, eps) not in best or r["us"] < best[name, eps]["us"]:
                    best[name, eps] = r
    lines = [f"load average {os.getloadavg()[0]:.2f}; rtol {DEFAULT_TOLERANCE:g} (the default)", "",
             "| eps | old us/case (slowest) | old abs(w-w_ref) | new us/case (slowest) | new/old | new fixed us/run "
             "| new abs(w-w_ref) |", "|---|---|---|---|---|---|---|"]
    for eps in epsilons:
        o, n = best["old", eps], best["new", eps]
        lines.append(f"| {eps:.0e} | {o['us']:.1f} ({o['us_max']:.1f}) | {o['err']:.1e} | {n['us']:.1f} "
                     f"({n['us_max']:.1f}) | {n['us'] / o['us']:.2f} | {n['fixed']:.2f} | {n['err']:.1e} |")
    return lines


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    print("\n".join(compare(sys.argv[1], sys.argv[2])))
