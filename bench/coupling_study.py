# SPDX-License-Identifier: BSD-2-Clause
"""The convergence study of docs/coupling.md: the coupled rod on the shaker table with
both couplings (the step means, the instantaneous forces), in each master.

- momentum: the residual of the system's vertical momentum balance (coupled.momentum_balance)
  relative to the rod's contact impulse, the models' defaults to 0.3 s, h = 1e-3, 1e-4, 1e-5;
- distance to a fine-step run: max over the trajectory of |q_h - q_ref| (fmpy, the mean coupling
  at h = 1e-5 for the defaults; h = 2.5e-5 for the soft case), each state;
- energy: an elastic, frictionless contact on an undamped, undriven table (nothing dissipates,
  nothing drives): E(T) - E(0) of rod plus table, E(0) from the start values.

    .venv/bin/python bench/coupling_study.py [--masters fmpy,libcosim,ecos]
"""
import argparse

import numpy as np

from painleve.coupling.coupled import COUPLINGS, Setup, initial_energy, momentum_balance, run_coupled, total_energy

ROD, TABLE = "build/PainleveRodSI.fmu", "build/ShakerTable.fmu"
STATES = ("rod.y", "rod.w", "rod.theta", "rod.phi", "table.position", "table.velocity")
STOP = 0.3
SOFT = Setup(rod=dict(k=2e5, c=450.0, mu=0.3, v=1.5, phi=0.0, theta=1.0), table=dict(belt_speed=0.5))
CONSERVATIVE = Setup(rod=dict(k=2e5, c=0.0, mu=0.0), table=dict(C=0.0, F0=0.0))


def distance(r, ref, h, h_ref):
    stride = round(h / h_ref)
    rr = ref[stride - 1::stride]
    return {n: float(np.max(np.abs(r[n] - rr[n]))) for n in STATES}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--masters", default="fmpy,libcosim,ecos")
    args = parser.parse_args()
    steps = (1e-3, 1e-4, 1e-5)
    print("| master | coupling | " + " | ".join(f"h = {h:g}" for h in steps) + " |")
    print("|---" * (2 + len(steps)) + "|")
    fine = {}
    for master in args.masters.split(","):
        for coupling in COUPLINGS:
            cells = []
            for h in steps:
                r = run_coupled(ROD, TABLE, Setup(), stop_time=STOP, step=h, master=master, coupling=coupling)
                b = momentum_balance(r, Setup(), h, coupling)
                cells.append(f"{b.residual / b.contact:+.1e}")
                if master == "fmpy":
                    fine[(coupling, h)] = r
            print(f"| {master} | {coupling} | " + " | ".join(cells) + " |", flush=True)
    for name, setup, stop, hs, h_ref in (("defaults", Setup(), STOP, steps, 1e-5),
                                         ("soft", SOFT, 0.1, (4e-4, 2e-4, 1e-4, 5e-5), 2.5e-5)):
        print(f"\ndistance to the mean coupling at h = {h_ref:g} ({name}, fmpy)")
        ref = fine.get(("mean", h_ref)) if name == "defaults" else None
        if ref is None:
            ref = run_coupled(ROD, TABLE, setup, stop_time=stop, step=h_ref)
        print("| coupling | h | " + " | ".join(STATES) + " |")
        print("|---" * (2 + len(STATES)) + "|")
        for coupling in COUPLINGS:
            for h in hs:
                r = fine.get((coupling, h)) if name == "defaults" else None
                if r is None:
                    r = run_coupled(ROD, TABLE, setup, stop_time=stop, step=h, coupling=coupling)
                d = distance(r, ref, h, h_ref)
                print(f"| {coupling} | {h:g} | " + " | ".join(f"{d[n]:.2e}" for n in STATES) + " |", flush=True)
    E0 = initial_energy(CONSERVATIVE)
    print(f"\nenergy, conservative system (E(0) = {E0:.6g} J): E(T) - E(0) and max E - E(0) at T = {STOP}")
    print("| coupling | h | E(T) - E(0) [J] | max(E - E(0)) [J] |\n|---|---|---|---|")
    for coupling in COUPLINGS:
        for h in steps:
            r = run_coupled(ROD, TABLE, CONSERVATIVE, stop_time=STOP, step=h, coupling=coupling)
            E = total_energy(r) - E0
            print(f"| {coupling} | {h:g} | {E[-1]:+.2e} | {np.max(E):+.2e} |", flush=True)


if __name__ == "__main__":
    main()
