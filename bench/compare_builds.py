# SPDX-License-Identifier: BSD-2-Clause
"""Did the physics move? Runs the benchmark's IWC cases (bench.py's cases_at,
eps = 1e-2 ... 1e-6) through two builds of PainleveRod.fmu, Model Exchange and
Co-Simulation, and prints w, phi, v at the return side by side with their
relative differences. Exit status 1 if any differs by more than --rtol.

    .venv/bin/python bench/compare_builds.py OLD.fmu NEW.fmu [--rtol 1e-12] [--tolerance 1e-11]

--tolerance: the FMUs' relative tolerance for every run (default: the harness's, min(1e-6, eps/100)).
"""
import argparse
import sys

from bench import cases_at
from painleve.fmu.experiment import Experiment

QUANTITIES = ("w", "phi", "v")


def outcomes(fmu, interface, epsilons, tolerance=None):
    with Experiment(fmu, fmi_type=interface) as experiment:
        experiment.relative_tolerance = tolerance
        return [experiment.run(case) for eps in epsilons for case in cases_at(eps)]


def relative(a, b):
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--rtol", type=float, default=1e-12)
    parser.add_argument("--tolerance", type=float, default=None)
    args = parser.parse_args()
    epsilons = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6)
    worst = 0.0
    print("| interface | eps | theta0 | delta | w10 | " + " | ".join(f"{q} old | {q} new | rel. diff" for q in QUANTITIES)
          + " |")
    print("|---" * (5 + 3 * len(QUANTITIES)) + "|")
    for interface in ("ModelExchange", "CoSimulation"):
        for old, new in zip(outcomes(args.old, interface, epsilons, args.tolerance),
                            outcomes(args.new, interface, epsilons, args.tolerance)):
            c = old.case
            cells = []
            for q in QUANTITIES:
                a, b = getattr(old, q), getattr(new, q)
                worst = max(worst, relative(a, b))
                cells.append(f"{a:.15g} | {b:.15g} | {relative(a, b):.1e}")
            print(f"| {interface} | {c.epsilon:g} | {c.theta0:g} | {c.delta:g} | {c.w10:.4g} | " + " | ".join(cells)
                  + " |")
    print(f"\nlargest relative difference: {worst:.2e} (allowed {args.rtol:g})")
    return 0 if worst <= args.rtol else 1


if __name__ == "__main__":
    sys.exit(main())
