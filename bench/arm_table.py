# SPDX-License-Identifier: BSD-2-Clause
"""The two-link arm's Co-Simulation table, as the rod's: TwoLinkArm (fmu_src/models/TwoLinkArm) as the tests' arm (tests/helpers/arm_lagrange:
H = 0.3, links of 0.5 and masses 0.5, L = M = g = 1, mu = 1.5), its tip on the floor moving
at (v0, 0), theta1 = 2.9 (v0 = 0.3) and 0.2 (v0 = 0.5), delta = 0.5 and 1 (k = M g / (L eps^2),
c = delta sqrt(M k)): each an impact without collision, slip, stick, slip, lift-off. Each case
runs through one fmi2DoStep from 0 to the reference's return of the tip to y = 0, from Python
through fmpy on one instance: fmi2Reset, setup with the tolerance, the parameters and states
set, initialization, the step, the state read.

    .venv/bin/python bench/arm_table.py          # prints the markdown table (~2 minutes)
    .venv/bin/python bench/arm_table.py --equal [--fmu ARM.fmu] [EPS ...]
        # each eps at its loosest rtol within 1e-6 relative in w

Per eps, at the FMU's default tolerance (1e-6) and at the harness's min(1e-6, eps/100): the
largest |w - w_ref| at the reference's return (w_ref: the tests' independent numpy arm,
Lagrange's equations in its own angles, under scipy DOP853 at rtol 1e-12; |w - w_ref| at
the same instant, relative to v0), us per case (median over cases of the median over
repeats; fmpy's calls included), the fixed cost (the same run without its fmi2DoStep) and
the FMU's switches."""
import pathlib
import sys

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(HERE))

from helpers.arm_lagrange import Arm, floor_angle, rates          # noqa: E402
from helpers.two_link_arm_iwc import simulate                       # noqa: E402
from bench_runners import load_line                                       # noqa: E402
from one_step_table import REPEATS, header, row, timed_run                     # noqa: E402
from painleve.fmu.experiment import Experiment                       # noqa: E402

ARM_FMU = ROOT / "build" / "TwoLinkArm.fmu"
ARM = Arm(H=0.3, mu=1.5)
CASES = [(theta1, v0, delta) for theta1, v0 in ((2.9, 0.3), (0.2, 0.5)) for delta in (0.5, 1.0)]
EPSILONS = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6)
WHERE_THE_TIME_GOES = (
    "Where the arm's time goes (perf over 53,000 runs of its four cases at eps = 1e-4, default tolerance): 57"
    ' % in the FMU, its own code 33 % and libm 24 % (the sines and cosines of the two angles and of their '
    "difference in every right-hand side: the mass matrix, the tip's Jacobian rows, the coefficients; pow in "
    "the step control), 34 % in Python, ctypes and libffi (fmpy's eight calls a run, most of the fixed 21-25 "
    'us: the reset, the set-up, 17 values set, initialization, the reads), the rest libc and the kernel. It '
    'costs 1.3-1.4 times the SI rod at the default tolerance (72-89 us against 51-69 us): the trigonometry of'
    ' two angles and a 2x2 mass matrix in every right-hand side. Its error at the default tolerance stays '
    "within 4e-7 v0 at every eps, eps = 1e-2 included: the reference's return is after eps ln(1/eps) of "
    "contact and a short flight, so no long flight is integrated, unlike the rod's horizon at eps = 1e-2. At "
    "the harness's tolerance it is 1.3-1.5e-8 (tests/bench/test_arm_table.py checks 1e-6 v0 at eps = 1e-2, "
    '1e-3, 1e-5).')


def start(theta1, v0, eps, delta):
    """The FMU's start values: the tests' arm, its tip on the floor moving at (v0, 0)."""
    th = np.array([theta1, floor_angle(ARM, theta1, 1)])
    om = rates(ARM, th, v0, 0.0)
    k = ARM.M * ARM.g / (ARM.L * eps ** 2)
    return th, om, dict(H=ARM.H, m1=ARM.m1, l1=ARM.l1, J1=ARM.J1, m2=ARM.m2, l2=ARM.l2, J2=ARM.J2, g=ARM.g,
                        mu=ARM.mu, k=k, c=delta * np.sqrt(ARM.M * k), kappa=0.0, beta=0.0,
                        theta1=th[0], theta2=th[1], omega1=om[0], omega2=om[1])


def reference(theta1, v0, eps, delta):
    """(t, w) at the tip's return to y = 0: the numpy arm under DOP853 at 1e-12."""
    th, om, _ = start(theta1, v0, eps, delta)
    out = simulate(ARM, th, om, eps, delta, t_max=5.0, rtol=1e-12)
    return out["t"], out["w"]


def read_tip(fmu, vr):
    """(w, contact) of the tip."""
    return fmu.getReal([vr["w"]])[0], fmu.getBoolean([vr["contact"]])[0]


def run_once(ex, values, rtol, stop, step=True):
    """One run; (seconds, w at `stop`, switches, contact at `stop`)."""
    seconds, (w, contact), switches = timed_run(ex, values, rtol, stop, read_tip, step)
    return seconds, w, switches, contact


def error(eps, theta1, v0, w_ref):
    """|w - w_ref| / v0 of an outcome (w, contact) at the reference's return."""
    def of(outcome):
        w, contact = outcome
        assert not contact, f"the tip is still in contact at the reference's return (eps {eps}, case {theta1})"
        return abs(w - w_ref) / v0
    return of


def arm_row(ex, eps, rtol, label, refs):
    cases = []
    for (theta1, v0, delta), (t_ref, w_ref) in zip(CASES, refs):
        values = start(theta1, v0, eps, delta)[2]
        cases.append((lambda step, values=values, t_ref=t_ref: timed_run(ex, values, rtol, t_ref, read_tip, step),
                      error(eps, theta1, v0, w_ref)))
    return row(eps, rtol, label, cases)


def arm_markdown(epsilons=EPSILONS):
    lines = ["## The two-link arm (TwoLinkArm): one fmi2DoStep per case from Python", "",
             __doc__.split("\n\n", 2)[2].replace("\n", " "), "", *header("abs(w-w_ref)/v0")]
    with Experiment(ARM_FMU, fmi_type="CoSimulation") as ex:
        for eps in epsilons:
            refs = [reference(theta1, v0, eps, delta) for theta1, v0, delta in CASES]
            lines.append(arm_row(ex, eps, 1e-6, "default", refs))
            if eps / 100 < 1e-6:
                lines.append(arm_row(ex, eps, eps / 100, "harness", refs))
    return lines + ["", WHERE_THE_TIME_GOES]


# Equal accuracy, as bench/limit_compare.py measures the rod: the loosest rtol of bench.py's ladder
# at which every case's w at the reference's return is within TARGET relative of w_ref.
LADDER = tuple(10 ** (-k / 2) for k in range(6, 23))    # 1e-3 ... 1e-11
TARGET = 1e-6


def equal_accuracy(ex, eps, refs, ladder=LADDER, target=TARGET):
    """(rtol, largest |w - w_ref| / |w_ref|) at the loosest rung within target; (None, None) if none is."""
    for rtol in ladder:
        errs = []
        for (theta1, v0, delta), (t_ref, w_ref) in zip(CASES, refs):
            _, w, _, contact = run_once(ex, start(theta1, v0, eps, delta)[2], rtol, t_ref)
            errs.append(abs(w - w_ref) / abs(w_ref) if not contact else float("inf"))
        if max(errs) <= target:
            return rtol, max(errs)
    return None, None


def equal_accuracy_rows(ex, epsilons=EPSILONS, rounds=5):
    """One dict per eps: rtol, err, us (median over cases of the median over rounds of
    one_step_table's medians), us_max (the slowest case), fixed (the run without its step)."""
    import statistics
    out = []
    for eps in epsilons:
        refs = [reference(theta1, v0, eps, delta) for theta1, v0, delta in CASES]
        rtol, err = equal_accuracy(ex, eps, refs)
        r = dict(eps=eps, rtol=rtol, err=err)
        if rtol is not None:
            walls, fixed = [[] for _ in CASES], [[] for _ in CASES]
            for _ in range(rounds):
                for i, ((theta1, v0, delta), (t_ref, _)) in enumerate(zip(CASES, refs)):
                    values = start(theta1, v0, eps, delta)[2]
                    walls[i].append(statistics.median(run_once(ex, values, rtol, t_ref)[0] for _ in range(REPEATS)))
                    fixed[i].append(statistics.median(run_once(ex, values, rtol, t_ref, step=False)[0]
                                                      for _ in range(REPEATS)))
            per_case = [1e6 * statistics.median(w) for w in walls]
            r.update(us=statistics.median(per_case), us_max=max(per_case),
                     fixed=1e6 * statistics.median(statistics.median(f) for f in fixed))
        out.append(r)
    return out


def equal_accuracy_markdown(rows, load_before, load_after):
    lines = [load_line(load_before, load_after),
             "", "| eps | FMU rtol | FMU us/case (slowest) | fixed us/run (fmpy's calls) | step us/case | "
             "max rel. err w |", "|---|---|---|---|---|---|"]
    for r in rows:
        if r["rtol"] is None:
            lines.append(f"| {r['eps']:.0e} | none of the ladder within {TARGET:g} | | | | |")
            continue
        lines.append(f"| {r['eps']:.0e} | {r['rtol']:.2g} | {r['us']:.1f} ({r['us_max']:.1f}) | {r['fixed']:.1f} | "
                     f"{r['us'] - r['fixed']:.1f} | {r['err']:.1e} |")
    return lines


def arm_equal_markdown(epsilons=EPSILONS, fmu=ARM_FMU):
    """The section for docs/benchmarks.md (bench.py)."""
    import os
    before = os.getloadavg()
    with Experiment(fmu, fmi_type="CoSimulation") as ex:
        rows = equal_accuracy_rows(ex, epsilons)
    return ["## The two-link arm at equal accuracy", "",
            "TwoLinkArm's four cases (above) per eps at the loosest rtol of bench.py's ladder at which every "
            "case's w at the numpy arm's return is within 1e-6 relative of it (the rod's criterion in the "
            "speed limit's table), timed there: one fmi2DoStep per case from Python through fmpy (medians of "
            f"{REPEATS} runs, median over 5 rounds, median over cases; the slowest case in brackets), the "
            "same run without its step (fmpy's calls: reset, set-up, values, initialization, reads) and the "
            "difference, the step's own cost, the figure that compares with the rod's us per case from C "
            "(whose fixed cost is about 2 us). There is no single-purpose arm to give a ratio.", ""] + \
        equal_accuracy_markdown(rows, before, os.getloadavg())


if __name__ == "__main__":
    args = sys.argv[1:]
    if args[:1] == ["--equal"]:
        import os
        fmu = args[2] if args[1:2] == ["--fmu"] else ARM_FMU
        args = args[3:] if args[1:2] == ["--fmu"] else args[1:]
        before = os.getloadavg()
        with Experiment(fmu, fmi_type="CoSimulation") as ex:
            rows = equal_accuracy_rows(ex, tuple(float(e) for e in args) or EPSILONS)
        print("\n".join(equal_accuracy_markdown(rows, before, os.getloadavg())))
    else:
        print("\n".join(arm_markdown(tuple(float(e) for e in args) or EPSILONS)))
