# SPDX-License-Identifier: BSD-2-Clause
"""The rigid rod's coefficients (Hogan & Kristiansen, eq coeffs and eq Sw), the Painleve
wedge (eqs mucrit, thetacrit), the quadrants of figure fig:GB, the fast eigenvalues of
compressed contact (eq lambdapm: analytic's Theorem 1 and rigid_limit both start from them), and the hypotheses of
Theorems 1 and 2 on them. Equation names in comments are the paper's ``\\eqlab`` labels.
All functions broadcast over numpy arrays; scalar input gives float output."""
import numpy as np

from .hypotheses import Hypotheses, as_result, floats, fmt, rod_parameters

ALPHA = 3.0  # uniform rod
MU = 3.0


def a(theta, phi):
    """a = -phi^2 cos(theta)."""
    return as_result(-floats(phi) ** 2 * np.cos(theta))  # eq coeffs


def b(theta, phi):
    """b = -1 + phi^2 sin(theta): free vertical acceleration of the end A."""
    return as_result(-1.0 + floats(phi) ** 2 * np.sin(theta))  # eq coeffs


# q_s, p_s, c_s for slip direction s = +1 (forward) or -1 (backward), and S_w, unchecked
# (the public functions below check the rod's parameters first).
def q_of(theta, s, alpha, mu):
    sn, cs = np.sin(theta), np.cos(theta)
    return alpha * sn * cs - s * mu * (1.0 + alpha * sn ** 2)  # eq coeffs


def p_of(theta, s, alpha, mu):
    sn, cs = np.sin(theta), np.cos(theta)
    return 1.0 + alpha * cs ** 2 - s * mu * alpha * sn * cs  # eq coeffs


def c_of(theta, s, alpha, mu):
    return -alpha * (np.cos(theta) - s * mu * np.sin(theta))  # eq coeffs


def q_plus(theta, *, alpha=ALPHA, mu=MU):
    """q_+ = alpha sin cos - mu (1 + alpha sin^2) (forward slip, v > 0)."""
    return as_result(q_of(floats(theta), 1.0, *rod_parameters(alpha, mu)))


def q_minus(theta, *, alpha=ALPHA, mu=MU):
    """q_- = alpha sin cos + mu (1 + alpha sin^2) (backward slip, v < 0)."""
    return as_result(q_of(floats(theta), -1.0, *rod_parameters(alpha, mu)))


def p_plus(theta, *, alpha=ALPHA, mu=MU):
    """p_+ = 1 + alpha cos^2 - mu alpha sin cos."""
    return as_result(p_of(floats(theta), 1.0, *rod_parameters(alpha, mu)))


def p_minus(theta, *, alpha=ALPHA, mu=MU):
    """p_- = 1 + alpha cos^2 + mu alpha sin cos."""
    return as_result(p_of(floats(theta), -1.0, *rod_parameters(alpha, mu)))


def c_plus(theta, *, alpha=ALPHA, mu=MU):
    """c_+ = -alpha (cos - mu sin)."""
    return as_result(c_of(floats(theta), 1.0, *rod_parameters(alpha, mu)))


def c_minus(theta, *, alpha=ALPHA, mu=MU):
    """c_- = -alpha (cos + mu sin)."""
    return as_result(c_of(floats(theta), -1.0, *rod_parameters(alpha, mu)))


def s_w_of(theta, alpha):
    return (1.0 + alpha) / (1.0 + alpha * np.sin(theta) ** 2)  # eq Sw


def S_w(theta, *, alpha=ALPHA):
    """S_w = (1 + alpha)/(1 + alpha sin^2): sticking (Filippov) w' per unit F_N."""
    return as_result(s_w_of(floats(theta), rod_parameters(alpha, 0.0)[0]))


def S_phi(theta, *, alpha=ALPHA):
    """S_phi = -alpha cos/(1 + alpha sin^2): sticking phi' per unit F_N."""
    alpha = rod_parameters(alpha, 0.0)[0]
    theta = floats(theta)
    return as_result(-alpha * np.cos(theta) / (1.0 + alpha * np.sin(theta) ** 2))  # eq Sw


def lambda_of(p, delta):
    """(lambda_+, lambda_-) for p < 0, unchecked; lambda_- = p/lambda_+ avoids cancellation."""
    lp = -delta * p / 2 + np.sqrt(delta ** 2 * p ** 2 - 4 * p) / 2  # eq lambdapm
    return lp, p / lp  # lambda_+ lambda_- = p (eq lambdapm2)


def lambda_pm(theta0, delta, *, alpha=ALPHA, mu=MU):
    """Fast eigenvalues (lambda_+, lambda_-) of compressed contact, eq lambdapm.

    Requires p_+(theta0) < 0 (then lambda_- < 0 < lambda_+) and delta >= 0.
    """
    th, al, m = check_hypotheses("lambda_pm (eq lambdapm)", theta0, alpha, mu, delta=delta)
    lp, lm = lambda_of(p_of(th, 1.0, al, m), floats(delta))
    return as_result(lp), as_result(lm)


def _wedge_text(alpha, mu):
    mup = 2.0 * np.sqrt(1.0 + alpha) / alpha  # eq mucrit
    if mu <= mup:
        return (f"no Painleve wedge for alpha={alpha:g}, mu={mu:g} since "
                f"mu <= mu_P(alpha) = {mup:.4f}")
    t1, t2 = _thetas(alpha, mu)
    return f"Painleve wedge theta0 in ({t1:.4f}, {t2:.4f}) for alpha={alpha:g}, mu={mu:g}"


def _need_wedge(h, th, al, m):
    """p_+(theta0) < 0 and q_+(theta0) < 0 < q_-(theta0)."""
    t, a_, m_ = th.ravel(), al.ravel(), m.ravel()
    pp = p_of(th, 1.0, al, m)
    h.need(pp < 0, "p_+(theta0) < 0", lambda i: f"p_+({fmt(t[i])}) = {fmt(pp.ravel()[i])}",
           note=lambda i: _wedge_text(a_[i], m_[i]))
    qp, qm = q_of(th, 1.0, al, m), q_of(th, -1.0, al, m)
    h.need((qp < 0) & (qm > 0), "q_+(theta0) < 0 < q_-(theta0)",
           lambda i: (f"q_+({fmt(t[i])}) = {fmt(qp.ravel()[i])}, "
                      f"q_-({fmt(t[i])}) = {fmt(qm.ravel()[i])}"))


def _need_ab(h, th, ph, bsign, need_a):
    """sign(b(theta0, phi0)) = bsign and, if need_a, a(theta0, phi0) != 0."""
    bb, aa = -1.0 + ph ** 2 * np.sin(th), -ph ** 2 * np.cos(th)
    loc = lambda i: f"({fmt(th.ravel()[i])}, {fmt(ph.ravel()[i])})"  # noqa: E731
    hyp = "b(theta0, phi0) < 0" if bsign < 0 else "b(theta0, phi0) > 0"
    h.need(bb * bsign > 0, hyp, lambda i: f"b{loc(i)} = {fmt(bb.ravel()[i])}")
    if need_a:
        h.need(aa != 0, "a(theta0, phi0) != 0", lambda i: f"a{loc(i)} = {fmt(aa.ravel()[i])}")


def check_hypotheses(who, theta0, alpha, mu, *, phi0=None, bsign=0, need_a=False,
                     v0=None, delta=None, delta_pos=False, epsilon=None):
    """Check the hypotheses of `who`; return broadcast (theta0, alpha, mu) arrays."""
    alpha, mu = rod_parameters(alpha, mu, who)
    h = Hypotheses(who, theta0, alpha, mu, phi0, v0, delta, epsilon)
    h.scalar("v0", v0, lambda x: x > 0, "v0 > 0")
    if delta_pos:
        h.scalar("delta", delta, lambda x: x > 0, "delta > 0")
    else:
        h.scalar("delta", delta, lambda x: x >= 0, "delta >= 0")
    h.scalar("epsilon", epsilon, lambda x: (x > 0) & (x < 1), "0 < epsilon < 1")
    th, al, m = h.bc(theta0), h.bc(alpha), h.bc(mu)
    _need_wedge(h, th, al, m)
    if bsign:
        _need_ab(h, th, h.bc(phi0), bsign, need_a)
    h.done()
    return th, al, m


def check_theorem1(theta0, phi0, v0, *, alpha=ALPHA, mu=MU, delta=None):
    """Raise HypothesisError unless (theta0, phi0, v0) satisfies Theorem 1.

    Inconsistent case: p_+ < 0, b < 0, q_+ < 0 < q_-, a != 0, v0 > 0
    (and delta >= 0 if given).
    """
    check_hypotheses("Theorem 1", theta0, alpha, mu, phi0=phi0, bsign=-1, need_a=True,
           v0=v0, delta=delta)


def check_theorem2(theta0, phi0, v0, *, alpha=ALPHA, mu=MU, delta=None):
    """Raise HypothesisError unless (theta0, phi0, v0) satisfies Theorem 2.

    Indeterminate case: p_+ < 0, b > 0, q_+ < 0 < q_-, a != 0, v0 > 0
    (and delta >= 0 if given).
    """
    check_hypotheses("Theorem 2", theta0, alpha, mu, phi0=phi0, bsign=+1, need_a=True,
           v0=v0, delta=delta)


# ------------------------------------------------------------- Painleve wedge
def mu_P(alpha=ALPHA):
    """Critical friction mu_P = 2 sqrt(1+alpha)/alpha; p_+ < 0 somewhere iff mu > mu_P."""
    alpha = rod_parameters(alpha, 0.0, "mu_P")[0]
    return as_result(2.0 * np.sqrt(1.0 + alpha) / alpha)  # eq mucrit


def _thetas(alpha, mu):
    root = np.sqrt(mu ** 2 * alpha ** 2 - 4.0 * (1.0 + alpha))
    return np.arctan((mu * alpha - root) / 2), np.arctan((mu * alpha + root) / 2)  # eq thetacrit


def _wedge(alpha, mu, who):
    alpha, mu = rod_parameters(alpha, mu, who)
    h = Hypotheses(who, alpha, mu)
    al, m = h.bc(alpha).ravel(), h.bc(mu).ravel()
    h.need(mu > 2.0 * np.sqrt(1.0 + alpha) / alpha, "mu > mu_P(alpha) (a Painleve wedge)",
           lambda i: _wedge_text(al[i], m[i]))
    h.done()
    return _thetas(alpha, mu)


def theta_1(*, alpha=ALPHA, mu=MU):
    """Lower edge of the Painleve wedge, where p_+ = 0 (needs mu > mu_P)."""
    return as_result(_wedge(alpha, mu, "theta_1")[0])


def theta_2(*, alpha=ALPHA, mu=MU):
    """Upper edge of the Painleve wedge, where p_+ = 0 (needs mu > mu_P)."""
    return as_result(_wedge(alpha, mu, "theta_2")[1])


def quadrant(theta, phi, *, alpha=ALPHA, mu=MU):
    """Name of the fig:GB quadrant of (theta, phi) for forward slip (v > 0).

    "indeterminate" (b > 0, p_+ < 0), "lift-off" (b > 0, p_+ > 0),
    "slipping" (b < 0, p_+ > 0), "inconsistent" (b < 0, p_+ < 0).
    On a boundary, b = 0 counts as b < 0 and p_+ = 0 as p_+ > 0.
    """
    alpha, mu = rod_parameters(alpha, mu, "quadrant")
    up = floats(b(theta, phi)) > 0
    neg = p_of(floats(theta), 1.0, alpha, mu) < 0
    up, neg = np.broadcast_arrays(up, neg)
    names = np.array([["slipping", "inconsistent"], ["lift-off", "indeterminate"]])
    return as_result(names[up.astype(int), neg.astype(int)])
