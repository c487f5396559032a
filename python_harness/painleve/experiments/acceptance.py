# SPDX-License-Identifier: BSD-2-Clause
"""When a simulated rod agrees with Theorems 1 and 2: the one set of acceptance
rules, used by `painleve validate` and by the tests.

The thresholds come from the physics, not from one build's numbers. Theorem 1's
error is O(eps ln 1/eps): measured 1e-3 of e or less at eps = 1e-6 in the thin
wedge mu = 1.4, 1e-5 in the wide one. A wrong constant in the physics leaves an
error that does not fall (a 25% error in S_w leaves 2 to 20% at eps = 1e-6), so
the rule asks for both a small error at the smallest eps and errors that fall.
Theorem 2 above the separatrix predicts lift-off with w = O(eps).
"""
import numpy as np

# |w/v0 - e|/e (and |phi error|/|phi jump|) allowed at the smallest eps of a study (<= 1e-5).
ERROR_AT_SMALLEST_EPS = 0.01
# Relative errors below this are the solver's (tolerance ~1e-8 amplified along the unstable
# manifold), not the model's: they count as converged and need not fall further.
NOISE = 1e-4
# Falling with eps: the error at the smallest eps is at most this fraction of that at the largest.
FALLS_TO = 0.5
# With three or more errors above NOISE, their log-log slope against eps (eps ln 1/eps: a little under 1).
MIN_RATE = 0.6
# The asymptotic regime: gravity acts over a stick of fast time ~ delta while e ~ delta^-2.
REGIME = 2e-2           # eps (1 + delta)^3 <= REGIME
# Above w1*: the rod lifts off without sticking, 0 < w <= LIFT_OFF_W * eps.
LIFT_OFF_W = 5.0
# The IWC / lift-off boundary bisected on the FMU at eps = 1e-5 lies within this of w1* (relative).
SEPARATRIX_TOLERANCE = 0.02


# Why: e ~ delta^-2 for large delta while the corrections the theorems drop are O(eps) over a stick
# of fast time ~ 1 + delta, so their size relative to e is ~ eps (1 + delta)^3; the asymptotics
# (eps -> 0) describe a case only where that is small.
REGIME_RULE = "eps (1 + delta)^3 <= 2e-2"


def regime_measure(epsilon, delta):
    """eps (1 + delta)^3: the relative size of the corrections the paper's asymptotics drop."""
    return epsilon * (1 + delta) ** 3


def in_regime(epsilons, delta):
    """The epsilons at which a case with damping delta is in the asymptotic regime."""
    return [eps for eps in epsilons if regime_measure(eps, delta) <= REGIME]


def regime_of(case):
    """(inside, reason): whether the paper's asymptotics are expected to hold for `case`, and why."""
    measure = regime_measure(case.epsilon, case.delta)
    if measure <= REGIME:
        return True, f"eps (1 + delta)^3 = {measure:.3g} <= {REGIME:g}"
    return False, (f"eps (1 + delta)^3 = {measure:.3g} > {REGIME:g}: the corrections the asymptotics drop are of "
                   f"relative size eps (1 + delta)^3, so the predictions are not expected to hold; an eps below "
                   f"{REGIME / (1 + case.delta) ** 3:.2g} is inside")


def power_rate(epsilons, errors):
    """Slope of log|error| against log(eps): the order at which an error falls."""
    return float(np.polyfit(np.log(epsilons), np.log(np.abs(errors)), 1)[0])


def convergence_failures(epsilons, errors, *, tolerance=ERROR_AT_SMALLEST_EPS):
    """What is wrong (empty if nothing) with errors (relative, at decreasing epsilons) that
    Theorem 1 says tend to 0: too large at the smallest eps, not falling, or too slowly."""
    errors = np.abs(np.asarray(errors, dtype=float))
    failures = []
    if not np.all(np.isfinite(errors)):
        return [f"non-finite errors {errors.tolist()}"]
    if errors[-1] > tolerance:
        failures.append(f"|error| {errors[-1]:.2e} > {tolerance:g} at eps = {epsilons[-1]:g}")
    if not (errors[-1] <= NOISE or errors[-1] < FALLS_TO * errors[0]):
        failures.append(f"errors do not fall with eps: {', '.join(f'{x:.1e}' for x in errors)}")
    above = errors > NOISE
    if above.sum() >= 3:
        eps, err = np.asarray(epsilons)[above], errors[above]
        if np.any(np.diff(err[1:]) >= 0):       # the largest eps may be outside the asymptotic regime
            failures.append(f"errors not strictly falling: {', '.join(f'{x:.1e}' for x in err)}")
        if (rate := power_rate(eps, err)) <= MIN_RATE:
            failures.append(f"errors fall at rate {rate:.2f} <= {MIN_RATE}")
    return failures


def theorem1_failures(outcomes):
    """Theorem 1 (or 2 below w1*) on one case at decreasing eps: IWC at every eps, and the
    errors of w/v0 (relative to e) and of phi (relative to its jump) converge."""
    from ..theory.analytic import predict
    predicted = predict(outcomes[0].case)
    epsilons = [o.case.epsilon for o in outcomes]
    failures = [] if all(o.iwc for o in outcomes) else ["no IWC at some eps"]
    failures += [f"w: {f}" for f in convergence_failures(epsilons, [o.w_error / predicted.e for o in outcomes])]
    if predicted.theorem == 1:
        jump = abs(predicted.phi - outcomes[0].case.phi0)
        failures += [f"phi: {f}" for f in convergence_failures(epsilons, [o.phi_error / jump for o in outcomes])]
    return failures


def lift_off_failures(outcomes):
    """Theorem 2 above w1*: lift-off without sticking, 0 < w <= LIFT_OFF_W eps, at each eps."""
    failures = ["stuck at some eps"] if any(o.iwc for o in outcomes) else []
    ratios = [o.w / o.case.epsilon for o in outcomes]
    if not all(0 < r <= LIFT_OFF_W for r in ratios):
        failures.append(f"w/eps = {', '.join(f'{r:.3g}' for r in ratios)} not in (0, {LIFT_OFF_W:g}]")
    return failures


def separatrix_gap(found, w1_star):
    """How far the bisected boundary lies from w1*, relative; accepted up to SEPARATRIX_TOLERANCE."""
    return abs(found - w1_star) / abs(w1_star)
