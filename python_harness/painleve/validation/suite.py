# SPDX-License-Identifier: BSD-2-Clause
"""The validation suite for any build of PainleveRod.fmu: what a CI pipeline
that ships the FMU runs (`painleve validate FMU`).

1. static: fmpy's validation of the archive and modelDescription.xml, and
   the interface contract of docs/model.md §4 (names, causality, variability, starts);
2. the default experiment, as any FMI tool would run it, shows an IWC;
3. Theorem 1 on a fixed set of cases across the parameter space (both Painleve
   wedges of the paper, other rods, every damping regime) and a seeded random
   sample: at eps = 1e-4, 1e-5, 1e-6 the lift-off velocity w/v0 tends to
   e(delta, theta0) and phi to the predicted value;
4. Theorem 2 in the indeterminate quadrant: IWC with the same e below the
   separatrix w1*, lift-off with w = O(eps) above it, and the boundary found by
   bisection on the FMU close to w1*.

The acceptance rules and their thresholds are acceptance.py's, shared with the tests.
Each interface the FMU declares (Model Exchange, Co-Simulation) is checked."""
import math
from dataclasses import asdict, replace

import numpy as np

from ..experiments import acceptance
from ..experiments.case import Case
from ..experiments.outcome import SimulationError
from ..experiments.studies import separatrix
from ..fmu.body import Body
from ..fmu.experiment import FMI_TYPES
from ..theory import analytic as an
from .report import Check
from .static import default_experiment_check, static_checks

EPSILONS = (1e-4, 1e-5, 1e-6)


# ------------------------------------------------------------------ the cases
def wedge_theta(alpha, mu, fraction):
    t1, t2 = an.theta_1(alpha=alpha, mu=mu), an.theta_2(alpha=alpha, mu=mu)
    return float(t1 + fraction * (t2 - t1))


def theorem1_cases(sample=24, seed=0):
    """(name, Case) pairs: fixed cases across both wedges and damping regimes, then a seeded random sample."""
    cases = []
    for f in (0.2, 0.5, 0.8):
        for delta in (0.0, 1.0, 4.0):
            cases.append((f"wide-f{f}-d{delta:g}", Case(alpha=3.0, mu=3.0, theta0=wedge_theta(3, 3, f), delta=delta)))
    cases += [
        ("wide-v2-phi0.2", Case(alpha=3.0, mu=3.0, theta0=wedge_theta(3, 3, 0.5), delta=1.0, v0=2.0, phi0=0.2)),
        ("wide-v0.5-phi0.8", Case(alpha=3.0, mu=3.0, theta0=wedge_theta(3, 3, 0.35), delta=0.5, v0=0.5, phi0=0.8)),
        ("alpha2-mu3", Case(alpha=2.0, mu=3.0, theta0=wedge_theta(2, 3, 0.5), delta=0.5)),
        ("alpha6-mu2", Case(alpha=6.0, mu=2.0, theta0=wedge_theta(6, 2, 0.5), delta=1.0)),
    ]
    for f in (0.25, 0.5, 0.75):
        for delta in (0.0, 1.0):
            cases.append((f"thin-f{f}-d{delta:g}", Case(alpha=3.0, mu=1.4, theta0=wedge_theta(3, 1.4, f), delta=delta)))
    rng = np.random.default_rng(seed)
    for k in range(sample):
        alpha = float(np.exp(rng.uniform(0.0, np.log(10.0))))
        mu = float(an.mu_P(alpha) * rng.uniform(1.5, 4.0))
        theta0 = wedge_theta(alpha, mu, rng.uniform(0.2, 0.8))
        phi0 = float(rng.uniform(0.1, 0.8) / math.sqrt(math.sin(theta0)))   # b < 0: phi0^2 sin(theta0) < 1
        cases.append((f"random-{k}", Case(alpha=alpha, mu=mu, theta0=theta0, phi0=phi0,
                                          delta=float(rng.uniform(0.0, 4.0)), v0=float(rng.uniform(0.5, 2.0)))))
    return cases


def theorem2_states():
    """(name, Case) pairs in the indeterminate quadrant (b > 0, p_+ < 0); w10 is set per check."""
    def up(alpha, mu, f, b, delta):
        th = wedge_theta(alpha, mu, f)
        return Case(alpha=alpha, mu=mu, theta0=th, phi0=math.sqrt((1 + b) / math.sin(th)), delta=delta)
    return [("video", Case(theta0=0.9463, phi0=1.6654, alpha=3.0, mu=3.0, delta=1.0)),
            ("wide-f0.3", up(3.0, 3.0, 0.3, 0.5, 0.5)),
            ("wide-f0.7-d0", up(3.0, 3.0, 0.7, 1.0, 0.0)),
            ("thin-f0.5", up(3.0, 1.4, 0.5, 0.5, 1.0)),
            ("alpha2-d2", up(2.0, 3.0, 0.5, 0.5, 2.0))]


def _label(case):
    law = f" kappa={case.kappa:.3g} beta={case.beta:.3g}" if case.kappa or case.beta else ""
    return (f"alpha={case.alpha:.3g} mu={case.mu:.3g} theta0={case.theta0:.4f} phi0={case.phi0:.4f} "
            f"v0={case.v0:.3g} delta={case.delta:.3g}{law}")


# ------------------------------------------------------------------ the checks
def theorem1_check(body, name, case, interface):
    epsilons = acceptance.in_regime(EPSILONS, case.delta)
    cid = f"theorem1/{interface}/{name}"
    try:
        outs = [body.run(replace(case, epsilon=eps)) for eps in epsilons]
    except SimulationError as err:
        return Check(cid, f"Theorem 1, {_label(case)}", f"simulation failed: {err}", "IWC", False)
    predicted = an.predict(case)
    w_err = np.array([o.w_error / predicted.e for o in outs])
    phi_err = np.array([o.phi_error / abs(predicted.phi - case.phi0) for o in outs])
    iwc = all(o.iwc for o in outs)
    failures = acceptance.theorem1_failures(outs)
    measured = (f"(w/v0-e)/e = {', '.join(f'{x:+.1e}' for x in w_err)}; phi err/jump = {phi_err[-1]:+.1e}"
                + ("" if iwc else "; no IWC at some eps"))
    return Check(cid, f"Theorem 1, {_label(case)}, eps = {', '.join(f'{e:g}' for e in epsilons)}", measured,
                 f"IWC; |err| <= {acceptance.ERROR_AT_SMALLEST_EPS:.0%} at eps={epsilons[-1]:g}; errors fall with eps",
                 not failures, dict(epsilons=epsilons, w_rel_errors=w_err.tolist(), phi_rel_errors=phi_err.tolist(),
                                    iwc=iwc, e=predicted.e, case=asdict(case), failures=failures))


def theorem2_checks(body, name, state, interface, epsilons=(1e-5, 1e-6)):
    predicted = an.predict(state)
    w1s = predicted.w1_star
    checks = []
    below, above = replace(state, w10=1.5 * w1s), replace(state, w10=0.5 * w1s)
    cid = f"theorem2/{interface}/{name}"
    tolerance = acceptance.ERROR_AT_SMALLEST_EPS
    try:
        outs = [body.run(replace(below, epsilon=eps)) for eps in epsilons]
        w_err = np.array([o.w_error / predicted.e for o in outs])
        iwc = all(o.iwc for o in outs)
        checks.append(Check(
            f"{cid}/below", f"Theorem 2 below w1* = {w1s:.4f} (w10 = 1.5 w1*), {_label(state)}, "
            f"eps = {', '.join(f'{e:g}' for e in epsilons)}",
            f"IWC {iwc}; (w/v0-e)/e = {', '.join(f'{x:+.1e}' for x in w_err)}",
            f"IWC; |err| <= {tolerance:.0%} at eps={epsilons[-1]:g}; errors fall",
            not acceptance.theorem1_failures(outs),
            dict(epsilons=list(epsilons), w_rel_errors=w_err.tolist(), iwc=iwc, w1_star=w1s, case=asdict(below))))
        outs = [body.run(replace(above, epsilon=eps)) for eps in epsilons]
        ratio = np.array([o.w / eps for o, eps in zip(outs, epsilons)])
        stuck = any(o.iwc for o in outs)
        checks.append(Check(
            f"{cid}/above", f"Theorem 2 above w1* = {w1s:.4f} (w10 = 0.5 w1*), {_label(state)}, "
            f"eps = {', '.join(f'{e:g}' for e in epsilons)}",
            f"IWC {stuck}; w/eps = {', '.join(f'{x:.3g}' for x in ratio)}",
            f"lift-off without sticking; 0 < w <= {acceptance.LIFT_OFF_W:g} eps",
            not acceptance.lift_off_failures(outs),
            dict(epsilons=list(epsilons), w_over_eps=ratio.tolist(), iwc=stuck, w1_star=w1s, case=asdict(above))))
    except SimulationError as err:
        checks.append(Check(cid, f"Theorem 2, {_label(state)}", f"simulation failed: {err}", "runs", False))
    return checks


def separatrix_check(body, name, state, interface, epsilon=1e-5):
    w1s = an.predict(state).w1_star
    cid = f"separatrix/{interface}/{name}"
    try:
        found = separatrix(body, replace(state, epsilon=epsilon), lower=2.0 * w1s, upper=0.5 * w1s,
                           tolerance=1e-3)
    except (ValueError, SimulationError) as err:
        return Check(cid, f"Theorem 2 separatrix at eps={epsilon:g}", f"bisection failed: {err}", "found", False)
    gap = acceptance.separatrix_gap(found, w1s)
    return Check(cid, f"Theorem 2 separatrix bisected on the FMU at eps={epsilon:g}, {_label(state)}",
                 f"w10 boundary {found:.4f} vs w1* {w1s:.4f} ({gap:.1%})",
                 f"within {acceptance.SEPARATRIX_TOLERANCE:.0%} of w1*", gap <= acceptance.SEPARATRIX_TOLERANCE,
                 dict(found=found, w1_star=w1s, relative_gap=gap))


def dynamic_checks(fmu_path, interface, *, sample=24, progress=None, law=None):
    """The theorems' checks through one interface, each case run by fmu.body.Body (the runner of every
    body FMU); law: the compliance law's kappa and beta for every case (their predictions then the
    rigid limit's, analytic.predict)."""
    law = law or {}
    checks = []
    try:
        body = Body(fmu_path, fmi_type=FMI_TYPES[interface])
    except Exception as err:      # the binary does not load or instantiate, or it is not a body FMU
        return [Check(f"instantiate/{interface}", f"instantiate through {interface}", f"failed: {err}",
                      "instantiates", False)]
    with body:
        for name, case in theorem1_cases(sample):
            checks.append(theorem1_check(body, name, replace(case, **law), interface))
            progress and progress(checks[-1])
        for name, state in theorem2_states():
            checks += theorem2_checks(body, name, replace(state, **law), interface)
            progress and progress(checks[-1])
        name, state = theorem2_states()[0]
        checks.append(separatrix_check(body, name, replace(state, **law), interface))
    return checks


def interfaces_of(fmu_path):
    from fmpy import read_model_description
    md = read_model_description(fmu_path)
    return [name for name, kind in (("ME", md.modelExchange), ("CS", md.coSimulation)) if kind is not None]


def validate(fmu_path, *, interfaces=None, sample=24, progress=None, law=None):
    """All checks for one FMU, in report order. Static failures stop before any simulation.
    law: {kappa, beta} of a nonlinear compliance law for every theorem case (default: linear)."""
    checks = static_checks(fmu_path)
    if not all(c.passed for c in checks):
        return checks
    for interface in interfaces or interfaces_of(fmu_path):
        checks.append(default_experiment_check(fmu_path, interface))
        checks += dynamic_checks(fmu_path, interface, sample=sample, progress=progress, law=law)
    return checks
