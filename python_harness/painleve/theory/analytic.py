# SPDX-License-Identifier: BSD-2-Clause
"""Analytic results of Hogan & Kristiansen for the compliant Painleve rod.

"On the regularization of impact without collision: the Painleve paradox and
compliance".  Equation names in comments are the paper's ``\\eqlab`` labels.
This module contains only the paper's formulas (numpy and scipy, no FMU); with
rod_coefficients (re-exported here) it is the whole of them:

* the rod coefficients a, b, q_pm, p_pm, c_pm (eq coeffs), the Filippov
  sticking coefficients S_w, S_phi (eq Sw), the Painleve wedge mu_P, theta_1,
  theta_2 (eqs mucrit, thetacrit), the quadrants of figure fig:GB and the fast
  eigenvalues lambda_pm (eq lambdapm): see rod_coefficients;
* the end of slipping compression (eqs z2EpsPi2, initStick), the "horizontal
  coefficient of restitution" e(delta, theta0) of Proposition prop:stick computed
  two ways (closed form eq eGeneral and exact integration of eq stickEps0), its
  asymptotes (eqs eDeltaLarge, eLarge, eDeltaSmall, eLow, eDeltaZero), the
  angular velocity after IWC (Theorem 1), the IWC time scale (eq TT) and the
  separatrix w1* of Theorem 2 (eq w1star);
* `predict(case)`: all of them for one experiment `Case`.

All functions broadcast over numpy arrays; scalar input gives float output.
Arguments outside a theorem's hypotheses raise :class:`HypothesisError`.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from . import general, rigid_limit
from .hypotheses import HypothesisError, as_result, floats
from .rod_coefficients import (ALPHA, MU, S_phi, S_w, a, b, c_minus, c_of, c_plus, check_hypotheses, check_theorem1,
                               check_theorem2, lambda_of, lambda_pm, mu_P, p_minus, p_of, p_plus, q_minus, q_of, q_plus,
                               quadrant, s_w_of, theta_1, theta_2)

__all__ = [
    "HypothesisError", "SlipCompressionEnd",
    "a", "b", "q_plus", "q_minus", "p_plus", "p_minus", "c_plus", "c_minus",
    "S_w", "S_phi", "mu_P", "theta_1", "theta_2", "quadrant", "lambda_pm",
    "slip_compression_end", "e_closed_form", "e_integrated", "e",
    "e_large_delta", "e_large_delta_rod", "e_small_delta", "e_zero",
    "phi_after_iwc", "iwc_time_scale", "w1_star",
    "check_theorem1", "check_theorem2", "Prediction", "predict", "check_case", "theorem_of",
]


# ------------------------------------------------------------------ Theorem 1
@dataclass(frozen=True)
class SlipCompressionEnd:
    """State where slipping compression ends (v = 0), eqs z2EpsPi2 / initStick."""

    yhat: object  # yhat = y/epsilon
    w: object
    phi: object


def slip_compression_end(theta0, phi0, v0, delta, *, alpha=ALPHA, mu=MU):
    """(yhat, w, phi) at the end of slipping compression, eq z2EpsPi2 (eps -> 0)."""
    th, al, m = check_hypotheses("Theorem 1", theta0, alpha, mu, v0=v0, delta=delta)
    pp, qp, cp = p_of(th, 1.0, al, m), q_of(th, 1.0, al, m), c_of(th, 1.0, al, m)
    lp = lambda_of(pp, floats(delta))[0]
    v0 = floats(v0)
    return SlipCompressionEnd(yhat=as_result(-pp * v0 / (qp * lp)),  # eq initStick
                              w=as_result(-pp * v0 / qp),
                              phi=as_result(floats(phi0) - cp * v0 / qp))


def _coeffs(delta, theta0, alpha, mu):
    th, al, m = check_hypotheses("Theorem 1", theta0, alpha, mu, delta=delta)
    return np.broadcast_arrays(floats(delta), th, p_of(th, 1.0, al, m), q_of(th, 1.0, al, m), s_w_of(th, al))


def e_closed_form(delta, theta0, *, alpha=ALPHA, mu=MU):
    """e(delta, theta0) from eq eGeneral with tau_s the least positive root: the general body's
    formula (general.e_of) on the rod's coefficients. Over-damped (real xi), critically damped
    (double root, as a limit) and oscillatory (complex xi) cases; see general.xi_tau.
    """
    delta, th, pp, qp, sw = _coeffs(delta, theta0, alpha, mu)
    return as_result(general.e_of(delta, pp, qp, sw))


def e_integrated(delta, theta0, *, alpha=ALPHA, mu=MU):
    """e(delta, theta0) by exact integration of the sticking system eq stickEps0.

    yhat' = w, w' = S_w(-yhat - delta w) is solved with the matrix exponential
    from eq initStick (v0 = 1) to the first root of yhat + delta w (Gamma_0),
    bracketed by stepping and refined with brentq; e = w there.
    """
    delta, th, pp, qp, sw = _coeffs(delta, theta0, alpha, mu)
    out = np.array([general.e_integrated_one(*args) for args in
                    zip(delta.ravel(), pp.ravel(), qp.ravel(), sw.ravel())]).reshape(delta.shape)
    return as_result(out)


def e(delta, theta0, *, alpha=ALPHA, mu=MU):
    """Horizontal coefficient of restitution e(delta, theta0) (closed form, eq eGeneral)."""
    return e_closed_form(delta, theta0, alpha=alpha, mu=mu)


def e_large_delta(delta, theta0, *, alpha=ALPHA, mu=MU):
    """Leading term of e for delta >> 1, eq eDeltaLarge (general q, p form)."""
    th, al, m = check_hypotheses("Theorem 1", theta0, alpha, mu, delta=delta, delta_pos=True)
    qp, qm, pp, pm = (f(th, s, al, m) for f in (q_of, p_of) for s in (1.0, -1.0))
    return as_result((pm - pp) / (qm * pp - qp * pm) * floats(delta) ** -2.0)  # eq eDeltaLarge


def e_large_delta_rod(delta, theta0, *, alpha=ALPHA, mu=MU):
    """Rod form of the delta >> 1 asymptote, alpha sin(2 theta0)/(2(1+alpha)) delta^-2."""
    th, al, _ = check_hypotheses("Theorem 1", theta0, alpha, mu, delta=delta, delta_pos=True)
    return as_result(al * np.sin(2 * th) / (2 * (1 + al)) * floats(delta) ** -2.0)  # eq eq:eDeltaLarge


def e_small_delta(delta, theta0, *, alpha=ALPHA, mu=MU):
    """Two-term expansion of e for delta << 1, eq eDeltaSmall (error O(delta^2))."""
    th, al, m = check_hypotheses("Theorem 1", theta0, alpha, mu, delta=delta)
    qp, qm, pp, pm = (f(th, s, al, m) for f in (q_of, p_of) for s in (1.0, -1.0))
    sw = s_w_of(th, al)
    e0 = np.sqrt(pp * (pm - pp) / (qp * (qm - qp)))  # eq eDeltaSmall
    slope = np.sqrt(sw) / 2 * (np.pi - np.arctan(np.sqrt(-sw / pp)))
    return as_result(e0 * (1 - slope * floats(delta)))


def e_zero(theta0, *, alpha=ALPHA, mu=MU):
    """e(0, theta0), eq eDeltaZero (its lone sin theta read as sin theta0)."""
    th, al, m = check_hypotheses("Theorem 1", theta0, alpha, mu)
    sn, cs = np.sin(th), np.cos(th)
    return as_result(np.sqrt((1 + al * cs ** 2 - m * al * sn * cs)
                        / (al * sn * cs - m * (1 + al * sn ** 2))
                        * al * sn * cs / (1 + al * sn ** 2)))  # eq eDeltaZero


def phi_after_iwc(theta0, phi0, v0, delta, *, alpha=ALPHA, mu=MU, e=None):
    """Angular velocity phi when the rod is back at y = 0 after IWC (Theorem 1, eq expr);
    e: the lift-off velocity over v0 if not the linear law's (rigid_limit.e for a nonlinear one)."""
    th, al, m = check_hypotheses("Theorem 1", theta0, alpha, mu, v0=v0, delta=delta)
    pp, qp, cp = p_of(th, 1.0, al, m), q_of(th, 1.0, al, m), c_of(th, 1.0, al, m)
    sphi = -al * np.cos(th) / (1 + al * np.sin(th) ** 2)
    ee = floats(e_closed_form(delta, th, alpha=al, mu=m) if e is None else e)
    return as_result(floats(phi0) + (-cp / qp + sphi / s_w_of(th, al) * (ee + pp / qp)) * floats(v0))  # eq expr


def iwc_time_scale(epsilon, theta0, delta, *, alpha=ALPHA, mu=MU):
    """Leading IWC duration epsilon ln(1/epsilon)/lambda_+ (eq TT, slow time)."""
    th, al, m = check_hypotheses("Theorem 1", theta0, alpha, mu, delta=delta, epsilon=epsilon)
    epsilon = floats(epsilon)
    return as_result(epsilon * np.log(1 / epsilon) / lambda_of(p_of(th, 1.0, al, m), floats(delta))[0])  # eq TT


def w1_star(theta0, phi0, delta, *, alpha=ALPHA, mu=MU):
    """Separatrix w1* = -lambda_- b/p_+ < 0 of Theorem 2, eq w1star (w = eps w10 at y = 0)."""
    th, al, m = check_hypotheses("Theorem 2", theta0, alpha, mu, phi0=phi0, bsign=+1, delta=delta)
    pp = p_of(th, 1.0, al, m)
    lm = lambda_of(pp, floats(delta))[1]
    return as_result(-lm * (-1.0 + floats(phi0) ** 2 * np.sin(th)) / pp)  # eq w1star


# ------------------------------------------------------------ one case's predictions
@dataclass(frozen=True)
class Prediction:
    """What the paper predicts for one IWC case (eps -> 0)."""
    theorem: int            # 1 (inconsistent quadrant, b < 0) or 2 (indeterminate, b > 0)
    e: float                # w/v0 at the return to y = 0 after IWC (Proposition prop:stick)
    phi: float              # phi there (Theorem 1, eq expr)
    lambda_plus: float      # the unstable eigenvalue of slipping compression (eq lambdapm)
    time_scale: float       # eps ln(1/eps)/lambda_+: the IWC's duration up to O(eps) (eq TT)
    w1_star: float          # Theorem 2's separatrix in w10 (eq w1star); NaN for Theorem 1
    iwc: bool               # Theorem 1, or Theorem 2 below the separatrix (None if w1* is undefined)


def theorem_of(case):
    """1 if the case starts in the inconsistent quadrant (b < 0), else 2."""
    return 1 if b(case.theta0, case.phi0) < 0 else 2


def check_case(case):
    """Raises HypothesisError, naming the hypothesis, unless Theorem 1 or 2 covers the Case
    (a fresh exception each time; the verdict is computed once per case, as predict's)."""
    if case in _INSIDE:
        return
    failure = hypothesis_failure(case)
    if failure is not None:
        raise HypothesisError(*failure)


@functools.lru_cache(maxsize=4096)
def hypothesis_failure(case):
    """(message, hypotheses) of the first failing hypothesis of the Case, or None."""
    try:
        if not (case.epsilon > 0 and np.isfinite(case.epsilon)):
            raise HypothesisError(f"epsilon must be > 0; got {case.epsilon}")
        theorem = theorem_of(case)
        check = check_theorem1 if theorem == 1 else check_theorem2
        check(case.theta0, case.phi0, case.v0, alpha=case.alpha, mu=case.mu, delta=case.delta)
        if theorem == 2 and not case.w10 < 0:
            raise HypothesisError(f"Theorem 2 starts the rod moving down, w10 < 0; got w10 = {case.w10}")
    except HypothesisError as err:
        return str(err), tuple(err.hypotheses)
    return None


def _or_nan(formula):
    """formula(), or NaN where the hypotheses of the result it evaluates fail."""
    try:
        return float(formula())
    except (ValueError, ArithmeticError):
        return np.nan


def _e_of(case, rod):
    """e of the case's compliance law: the paper's closed form for the linear law, the
    rigid limit computed numerically for a nonlinear one (rigid_limit)."""
    if not (case.kappa or case.beta):
        return e(case.delta, case.theta0, **rod)
    return float(rigid_limit.e(case.delta, case.theta0, kappa=case.kappa, beta=case.beta, v0=case.v0, **rod))


_SEEDED, _INSIDE = {}, set()    # a batch's predictions over arrays (predict_many), its cases inside


def seed_predictions(predictions):
    """{case: Prediction} of one batch's cases inside the hypotheses: predict returns (and caches) these
    instead of computing them, check_case passes these cases (the last batch's) without checking each.
    Only the last batch's are held: one that predict had cached already would stay seeded for ever."""
    _SEEDED.clear()
    _SEEDED.update(predictions)
    _INSIDE.clear()
    _INSIDE.update(predictions)


@functools.lru_cache(maxsize=4096)
def predict(case):
    """The paper's predictions for a Case, NaN where a result's hypotheses fail (see
    check_case); computed once per case, since a sweep asks for each several times.
    For a nonlinear compliance law (case.kappa, case.beta) e and phi are the rigid
    limit's; Theorem 2's w1* is the linear law's (the nonlinear terms are O(eps) in
    the initial layer, docs/nonlinear_compliance.md)."""
    if (seeded := _SEEDED.pop(case, None)) is not None:
        return seeded
    rod = dict(alpha=case.alpha, mu=case.mu)
    theorem = theorem_of(case)
    w1s = np.nan if theorem == 1 else _or_nan(lambda: w1_star(case.theta0, case.phi0, case.delta, **rod))
    ee = _or_nan(lambda: _e_of(case, rod))
    return Prediction(theorem=theorem, e=ee,
                      phi=_or_nan(lambda: phi_after_iwc(case.theta0, case.phi0, case.v0, case.delta, e=ee, **rod)),
                      lambda_plus=_or_nan(lambda: lambda_pm(case.theta0, case.delta, **rod)[0]),
                      time_scale=_or_nan(lambda: iwc_time_scale(case.epsilon, case.theta0, case.delta, **rod)),
                      w1_star=w1s, iwc=None if theorem == 2 and np.isnan(w1s) else theorem == 1 or case.w10 < w1s)
