# SPDX-License-Identifier: BSD-2-Clause
"""The two-link arm's Co-Simulation table (issue #28: "the two-link arm ... gets the same
table"): TwoLinkArm (fmu_src/models/TwoLinkArm) as the tests' arm (tests/helpers/arm_lagrange:
H = 0.3, links of 0.5 and masses 0.5, L = M = g = 1, mu = 1.5), its tip on the floor moving
at (v0, 0), theta1 = 2.9 (v0 = 0.3) and 0.2 (v0 = 0.5), delta = 0.5 and 1 (k = M g / (L eps^2),
c = delta sqrt(M k)): each an impact without collision, slip, stick, slip, lift-off. Each case
runs through one fmi2DoStep from 0 to the reference's return of the tip to y = 0, from Python
through fmpy on one instance: fmi2Reset, setup with the tolerance, the parameters and states
set, initialization, the step, the state read.

    .venv/bin/python bench/arm_table.py          # prints the markdown table (~2 minutes)

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
from one_step_table import header, row, timed_run                     # noqa: E402
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


if __name__ == "__main__":
    print("\n".join(arm_markdown(tuple(float(e) for e in sys.argv[1:]) or EPSILONS)))
