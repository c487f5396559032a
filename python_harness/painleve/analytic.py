"""Analytic results of Hogan & Kristiansen for the compliant Painleve rod.

"On the regularization of impact without collision: the Painleve paradox and
compliance".  Equation names in comments are the paper's ``\\eqlab`` labels.
This module contains only the paper's formulas (numpy and scipy, no FMU):

* the rod coefficients a, b, q_pm, p_pm, c_pm (eq coeffs) and the Filippov
  sticking coefficients S_w, S_phi (eq Sw);
* the Painleve wedge mu_P, theta_1, theta_2 (eqs mucrit, thetacrit) and the
  quadrants of figure fig:GB;
* the fast eigenvalues lambda_pm (eq lambdapm), the end of slipping
  compression (eqs z2EpsPi2, initStick), the "horizontal coefficient of
  restitution" e(delta, theta0) of Proposition prop:stick computed two ways
  (closed form eq eGeneral and exact integration of eq stickEps0), its
  asymptotes (eqs eDeltaLarge, eLarge, eDeltaSmall, eLow, eDeltaZero), the
  angular velocity after IWC (Theorem 1), the IWC time scale (eq TT) and the
  separatrix w1* of Theorem 2 (eq w1star).

All functions broadcast over numpy arrays; scalar input gives float output.
Arguments outside a theorem's hypotheses raise :class:`HypothesisError`.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import scipy.linalg
import scipy.optimize

__all__ = [
    "HypothesisError", "SlipCompressionEnd",
    "a", "b", "q_plus", "q_minus", "p_plus", "p_minus", "c_plus", "c_minus",
    "S_w", "S_phi", "mu_P", "theta_1", "theta_2", "quadrant", "lambda_pm",
    "slip_compression_end", "e_closed_form", "e_integrated", "e",
    "e_large_delta", "e_large_delta_rod", "e_small_delta", "e_zero",
    "phi_after_iwc", "iwc_time_scale", "w1_star",
    "check_theorem1", "check_theorem2", "Prediction", "predict", "check_case", "theorem_of",
]

ALPHA = 3.0  # uniform rod
MU = 3.0


class HypothesisError(ValueError):
    """Arguments outside the hypotheses of the paper's result being evaluated.

    ``hypotheses`` lists the failing hypotheses (as written in the message).
    """

    def __init__(self, message, hypotheses=()):
        super().__init__(message)
        self.hypotheses = list(hypotheses)


def _out(x):
    """Float for 0-d results, the array otherwise."""
    x = np.asarray(x)
    return x.item() if x.ndim == 0 else x


def _f(x):
    return np.asarray(x, dtype=float)


# ---------------------------------------------------------------- coefficients
def a(theta, phi):
    """a = -phi^2 cos(theta)."""
    return _out(-_f(phi) ** 2 * np.cos(theta))  # eq coeffs


def b(theta, phi):
    """b = -1 + phi^2 sin(theta): free vertical acceleration of the end A."""
    return _out(-1.0 + _f(phi) ** 2 * np.sin(theta))  # eq coeffs


def _q(theta, s, alpha, mu):
    sn, cs = np.sin(theta), np.cos(theta)
    return alpha * sn * cs - s * mu * (1.0 + alpha * sn ** 2)  # eq coeffs


def _p(theta, s, alpha, mu):
    sn, cs = np.sin(theta), np.cos(theta)
    return 1.0 + alpha * cs ** 2 - s * mu * alpha * sn * cs  # eq coeffs


def _c(theta, s, alpha, mu):
    return -alpha * (np.cos(theta) - s * mu * np.sin(theta))  # eq coeffs


def q_plus(theta, *, alpha=ALPHA, mu=MU):
    """q_+ = alpha sin cos - mu (1 + alpha sin^2) (forward slip, v > 0)."""
    return _out(_q(_f(theta), 1.0, *_params(alpha, mu)))


def q_minus(theta, *, alpha=ALPHA, mu=MU):
    """q_- = alpha sin cos + mu (1 + alpha sin^2) (backward slip, v < 0)."""
    return _out(_q(_f(theta), -1.0, *_params(alpha, mu)))


def p_plus(theta, *, alpha=ALPHA, mu=MU):
    """p_+ = 1 + alpha cos^2 - mu alpha sin cos."""
    return _out(_p(_f(theta), 1.0, *_params(alpha, mu)))


def p_minus(theta, *, alpha=ALPHA, mu=MU):
    """p_- = 1 + alpha cos^2 + mu alpha sin cos."""
    return _out(_p(_f(theta), -1.0, *_params(alpha, mu)))


def c_plus(theta, *, alpha=ALPHA, mu=MU):
    """c_+ = -alpha (cos - mu sin)."""
    return _out(_c(_f(theta), 1.0, *_params(alpha, mu)))


def c_minus(theta, *, alpha=ALPHA, mu=MU):
    """c_- = -alpha (cos + mu sin)."""
    return _out(_c(_f(theta), -1.0, *_params(alpha, mu)))


def _sw(theta, alpha):
    return (1.0 + alpha) / (1.0 + alpha * np.sin(theta) ** 2)  # eq Sw


def S_w(theta, *, alpha=ALPHA):
    """S_w = (1 + alpha)/(1 + alpha sin^2): sticking (Filippov) w' per unit F_N."""
    return _out(_sw(_f(theta), _params(alpha, 0.0)[0]))


def S_phi(theta, *, alpha=ALPHA):
    """S_phi = -alpha cos/(1 + alpha sin^2): sticking phi' per unit F_N."""
    alpha = _params(alpha, 0.0)[0]
    theta = _f(theta)
    return _out(-alpha * np.cos(theta) / (1.0 + alpha * np.sin(theta) ** 2))  # eq Sw


# ------------------------------------------------------------ hypothesis checks
def _fmt(x):
    return f"{float(x):.4g}"


class _Hypotheses:
    """Collects failing hypotheses of `who` over broadcast arrays, then raises once."""

    def __init__(self, who, *arrays):
        self.who, self.fails = who, []
        self.shape = np.broadcast_shapes(*(np.shape(x) for x in arrays if x is not None))

    def bc(self, x):
        return np.broadcast_to(_f(x), self.shape)

    def need(self, ok, hyp, got, note=None):
        """Record `hyp` if any element of ok is False; got(i)/note(i) describe flat element i."""
        bad = ~np.broadcast_to(np.asarray(ok, dtype=bool), self.shape)
        if bad.any():
            i = int(np.flatnonzero(bad.ravel())[0])
            where = (f" at element {tuple(int(k) for k in np.unravel_index(i, self.shape))}"
                     if self.shape else "")
            extra = f" ({note(i)})" if note else ""
            self.fails.append((hyp, f"{extra}; got {got(i)}{where}"))

    def scalar(self, name, x, ok_fn, hyp):
        if x is not None:
            xb = self.bc(x).ravel()
            self.need(ok_fn(self.bc(x)), hyp, lambda i: f"{name} = {_fmt(xb[i])}")

    def done(self):
        if self.fails:
            msg = "; ".join(f"{self.who} needs {hyp}{extra}" for hyp, extra in self.fails)
            raise HypothesisError(msg, [hyp for hyp, _ in self.fails])


def _params(alpha, mu, who="the rod model"):
    """alpha > 0 and mu >= 0, as float arrays."""
    h = _Hypotheses(who, alpha, mu)
    h.scalar("alpha", alpha, lambda x: x > 0, "alpha > 0")
    h.scalar("mu", mu, lambda x: x >= 0, "mu >= 0")
    h.done()
    return _f(alpha), _f(mu)


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
    pp = _p(th, 1.0, al, m)
    h.need(pp < 0, "p_+(theta0) < 0", lambda i: f"p_+({_fmt(t[i])}) = {_fmt(pp.ravel()[i])}",
           note=lambda i: _wedge_text(a_[i], m_[i]))
    qp, qm = _q(th, 1.0, al, m), _q(th, -1.0, al, m)
    h.need((qp < 0) & (qm > 0), "q_+(theta0) < 0 < q_-(theta0)",
           lambda i: (f"q_+({_fmt(t[i])}) = {_fmt(qp.ravel()[i])}, "
                      f"q_-({_fmt(t[i])}) = {_fmt(qm.ravel()[i])}"))


def _need_ab(h, th, ph, bsign, need_a):
    """sign(b(theta0, phi0)) = bsign and, if need_a, a(theta0, phi0) != 0."""
    bb, aa = -1.0 + ph ** 2 * np.sin(th), -ph ** 2 * np.cos(th)
    loc = lambda i: f"({_fmt(th.ravel()[i])}, {_fmt(ph.ravel()[i])})"  # noqa: E731
    hyp = "b(theta0, phi0) < 0" if bsign < 0 else "b(theta0, phi0) > 0"
    h.need(bb * bsign > 0, hyp, lambda i: f"b{loc(i)} = {_fmt(bb.ravel()[i])}")
    if need_a:
        h.need(aa != 0, "a(theta0, phi0) != 0", lambda i: f"a{loc(i)} = {_fmt(aa.ravel()[i])}")


def _check(who, theta0, alpha, mu, *, phi0=None, bsign=0, need_a=False,
           v0=None, delta=None, delta_pos=False, epsilon=None):
    """Check the hypotheses of `who`; return broadcast (theta0, alpha, mu) arrays."""
    alpha, mu = _params(alpha, mu, who)
    h = _Hypotheses(who, theta0, alpha, mu, phi0, v0, delta, epsilon)
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
    _check("Theorem 1", theta0, alpha, mu, phi0=phi0, bsign=-1, need_a=True,
           v0=v0, delta=delta)


def check_theorem2(theta0, phi0, v0, *, alpha=ALPHA, mu=MU, delta=None):
    """Raise HypothesisError unless (theta0, phi0, v0) satisfies Theorem 2.

    Indeterminate case: p_+ < 0, b > 0, q_+ < 0 < q_-, a != 0, v0 > 0
    (and delta >= 0 if given).
    """
    _check("Theorem 2", theta0, alpha, mu, phi0=phi0, bsign=+1, need_a=True,
           v0=v0, delta=delta)


# ------------------------------------------------------------- Painleve wedge
def mu_P(alpha=ALPHA):
    """Critical friction mu_P = 2 sqrt(1+alpha)/alpha; p_+ < 0 somewhere iff mu > mu_P."""
    alpha = _params(alpha, 0.0, "mu_P")[0]
    return _out(2.0 * np.sqrt(1.0 + alpha) / alpha)  # eq mucrit


def _thetas(alpha, mu):
    root = np.sqrt(mu ** 2 * alpha ** 2 - 4.0 * (1.0 + alpha))
    return np.arctan((mu * alpha - root) / 2), np.arctan((mu * alpha + root) / 2)  # eq thetacrit


def _wedge(alpha, mu, who):
    alpha, mu = _params(alpha, mu, who)
    h = _Hypotheses(who, alpha, mu)
    al, m = h.bc(alpha).ravel(), h.bc(mu).ravel()
    h.need(mu > 2.0 * np.sqrt(1.0 + alpha) / alpha, "mu > mu_P(alpha) (a Painleve wedge)",
           lambda i: _wedge_text(al[i], m[i]))
    h.done()
    return _thetas(alpha, mu)


def theta_1(*, alpha=ALPHA, mu=MU):
    """Lower edge of the Painleve wedge, where p_+ = 0 (needs mu > mu_P)."""
    return _out(_wedge(alpha, mu, "theta_1")[0])


def theta_2(*, alpha=ALPHA, mu=MU):
    """Upper edge of the Painleve wedge, where p_+ = 0 (needs mu > mu_P)."""
    return _out(_wedge(alpha, mu, "theta_2")[1])


def quadrant(theta, phi, *, alpha=ALPHA, mu=MU):
    """Name of the fig:GB quadrant of (theta, phi) for forward slip (v > 0).

    "indeterminate" (b > 0, p_+ < 0), "lift-off" (b > 0, p_+ > 0),
    "slipping" (b < 0, p_+ > 0), "inconsistent" (b < 0, p_+ < 0).
    On a boundary, b = 0 counts as b < 0 and p_+ = 0 as p_+ > 0.
    """
    alpha, mu = _params(alpha, mu, "quadrant")
    up = _f(b(theta, phi)) > 0
    neg = _p(_f(theta), 1.0, alpha, mu) < 0
    up, neg = np.broadcast_arrays(up, neg)
    names = np.array([["slipping", "inconsistent"], ["lift-off", "indeterminate"]])
    return _out(names[up.astype(int), neg.astype(int)])


# ------------------------------------------------------------------ Theorem 1
def _lam(p, delta):
    """(lambda_+, lambda_-) for p < 0; lambda_- = p/lambda_+ avoids cancellation."""
    lp = -delta * p / 2 + np.sqrt(delta ** 2 * p ** 2 - 4 * p) / 2  # eq lambdapm
    return lp, p / lp  # lambda_+ lambda_- = p (eq lambdapm2)


def lambda_pm(theta0, delta, *, alpha=ALPHA, mu=MU):
    """Fast eigenvalues (lambda_+, lambda_-) of compressed contact, eq lambdapm.

    Requires p_+(theta0) < 0 (then lambda_- < 0 < lambda_+) and delta >= 0.
    """
    th, al, m = _check("lambda_pm (eq lambdapm)", theta0, alpha, mu, delta=delta)
    lp, lm = _lam(_p(th, 1.0, al, m), _f(delta))
    return _out(lp), _out(lm)


@dataclass(frozen=True)
class SlipCompressionEnd:
    """State where slipping compression ends (v = 0), eqs z2EpsPi2 / initStick."""

    yhat: object  # yhat = y/epsilon
    w: object
    phi: object


def slip_compression_end(theta0, phi0, v0, delta, *, alpha=ALPHA, mu=MU):
    """(yhat, w, phi) at the end of slipping compression, eq z2EpsPi2 (eps -> 0)."""
    th, al, m = _check("Theorem 1", theta0, alpha, mu, v0=v0, delta=delta)
    pp, qp, cp = _p(th, 1.0, al, m), _q(th, 1.0, al, m), _c(th, 1.0, al, m)
    lp = _lam(pp, _f(delta))[0]
    v0 = _f(v0)
    return SlipCompressionEnd(yhat=_out(-pp * v0 / (qp * lp)),  # eq initStick
                              w=_out(-pp * v0 / qp),
                              phi=_out(_f(phi0) - cp * v0 / qp))


def _coeffs(delta, theta0, alpha, mu):
    th, al, m = _check("Theorem 1", theta0, alpha, mu, delta=delta)
    return np.broadcast_arrays(_f(delta), th, _p(th, 1.0, al, m), _q(th, 1.0, al, m), _sw(th, al))


def _xi_tau(delta, sw, lp):
    """Roots xi_pm of xi^2 + delta S_w xi + S_w = 0 and the least positive tau_s of eq eGeneral.

    Real case: tau_s = ln R/(xi_+ - xi_-), R = xi_-^2(lambda_+ - xi_+)/(xi_+^2(lambda_+ - xi_-)),
    evaluated as log1p(u)/u * S_w(1 + lambda_+ delta)/(xi_+^2(lambda_+ - xi_-)) with
    u = R - 1 = (xi_+ - xi_-) S_w(1 + lambda_+ delta)/(xi_+^2(lambda_+ - xi_-)), so the
    double root delta = 2/sqrt(S_w) is the analytic limit u -> 0.  Complex case
    xi_pm = -sigma +- i omega: tau_s = (varphi - pi n)/omega, n = floor(varphi/pi),
    varphi = arg((lambda_+ - xi_+) xi_-^2) (the paper's phi; its 2i/(xi_+ - xi_-) = 1/omega).
    """
    disc = delta ** 2 * sw ** 2 - 4 * sw
    real = disc >= 0
    dxi = np.sqrt(np.abs(disc)) * np.where(real, 1.0, 1j)  # xi_+ - xi_-
    xim = -(delta * sw + dxi) / 2
    xip = np.where(real, sw / xim, np.conj(xim))  # xi_+ xi_- = S_w, no cancellation
    with np.errstate(divide="ignore", invalid="ignore"):  # each branch is junk on the other's side
        k = (sw * (1 + lp * delta) / (xip ** 2 * (lp - xim))).real
        u = (dxi * k).real
        tau_real = np.where(u == 0, 1.0, np.log1p(u) / u) * k
        varphi = np.angle((lp - xip) * xim ** 2)
        tau_cplx = np.mod(varphi, np.pi) / (dxi.imag / 2)
    return xip, xim, np.where(real, tau_real, tau_cplx)


def e_closed_form(delta, theta0, *, alpha=ALPHA, mu=MU):
    """e(delta, theta0) from eq eGeneral with tau_s the least positive root.

    Over-damped (real xi), critically damped (double root, as a limit) and
    oscillatory (complex xi) cases; see _xi_tau.
    """
    delta, th, pp, qp, sw = _coeffs(delta, theta0, alpha, mu)
    lp = _lam(pp, delta)[0]
    xip, xim, tau = _xi_tau(delta, sw, lp)
    ee = (xip / xim) * (lp - xim) * pp / (qp * lp) * np.exp(xip * tau)  # eq eGeneral
    return _out(ee.real)


def _e_integrated_one(delta, pp, qp, sw):
    lp = _lam(pp, delta)[0]
    w0 = -pp / qp  # eq initStick with v0 = 1
    x0 = np.array([w0 / lp, w0])
    A = np.array([[0.0, 1.0], [-sw, -delta * sw]])  # eq stickEps0

    def state(t):
        return scipy.linalg.expm(A * t) @ x0

    def g(t):  # hat F_N = -yhat - delta w: positive while sticking, zero on Gamma_0
        return -(state(t) @ np.array([1.0, delta]))

    h = 0.25 / max(np.sqrt(sw), delta * sw)  # well below every time scale 1/|xi|
    t0, t1 = 0.0, h
    for _ in range(100000):
        if g(t1) <= 0:
            break
        t0, t1 = t1, t1 + h
    else:  # pragma: no cover - the root always exists (Proposition prop:stick)
        raise RuntimeError("no end of sticking found")
    ts = scipy.optimize.brentq(g, t0, t1, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=500)
    return state(ts)[1]


def e_integrated(delta, theta0, *, alpha=ALPHA, mu=MU):
    """e(delta, theta0) by exact integration of the sticking system eq stickEps0.

    yhat' = w, w' = S_w(-yhat - delta w) is solved with the matrix exponential
    from eq initStick (v0 = 1) to the first root of yhat + delta w (Gamma_0),
    bracketed by stepping and refined with brentq; e = w there.
    """
    delta, th, pp, qp, sw = _coeffs(delta, theta0, alpha, mu)
    out = np.array([_e_integrated_one(*args) for args in
                    zip(delta.ravel(), pp.ravel(), qp.ravel(), sw.ravel())]).reshape(delta.shape)
    return _out(out)


def e(delta, theta0, *, alpha=ALPHA, mu=MU):
    """Horizontal coefficient of restitution e(delta, theta0) (closed form, eq eGeneral)."""
    return e_closed_form(delta, theta0, alpha=alpha, mu=mu)


def e_large_delta(delta, theta0, *, alpha=ALPHA, mu=MU):
    """Leading term of e for delta >> 1, eq eDeltaLarge (general q, p form)."""
    th, al, m = _check("Theorem 1", theta0, alpha, mu, delta=delta, delta_pos=True)
    qp, qm, pp, pm = (f(th, s, al, m) for f in (_q, _p) for s in (1.0, -1.0))
    return _out((pm - pp) / (qm * pp - qp * pm) * _f(delta) ** -2.0)  # eq eDeltaLarge


def e_large_delta_rod(delta, theta0, *, alpha=ALPHA, mu=MU):
    """Rod form of the delta >> 1 asymptote, alpha sin(2 theta0)/(2(1+alpha)) delta^-2."""
    th, al, _ = _check("Theorem 1", theta0, alpha, mu, delta=delta, delta_pos=True)
    return _out(al * np.sin(2 * th) / (2 * (1 + al)) * _f(delta) ** -2.0)  # eq eq:eDeltaLarge


def e_small_delta(delta, theta0, *, alpha=ALPHA, mu=MU):
    """Two-term expansion of e for delta << 1, eq eDeltaSmall (error O(delta^2))."""
    th, al, m = _check("Theorem 1", theta0, alpha, mu, delta=delta)
    qp, qm, pp, pm = (f(th, s, al, m) for f in (_q, _p) for s in (1.0, -1.0))
    sw = _sw(th, al)
    e0 = np.sqrt(pp * (pm - pp) / (qp * (qm - qp)))  # eq eDeltaSmall
    slope = np.sqrt(sw) / 2 * (np.pi - np.arctan(np.sqrt(-sw / pp)))
    return _out(e0 * (1 - slope * _f(delta)))


def e_zero(theta0, *, alpha=ALPHA, mu=MU):
    """e(0, theta0), eq eDeltaZero (its lone sin theta read as sin theta0)."""
    th, al, m = _check("Theorem 1", theta0, alpha, mu)
    sn, cs = np.sin(th), np.cos(th)
    return _out(np.sqrt((1 + al * cs ** 2 - m * al * sn * cs)
                        / (al * sn * cs - m * (1 + al * sn ** 2))
                        * al * sn * cs / (1 + al * sn ** 2)))  # eq eDeltaZero


def phi_after_iwc(theta0, phi0, v0, delta, *, alpha=ALPHA, mu=MU):
    """Angular velocity phi when the rod is back at y = 0 after IWC (Theorem 1, eq expr)."""
    th, al, m = _check("Theorem 1", theta0, alpha, mu, v0=v0, delta=delta)
    pp, qp, cp = _p(th, 1.0, al, m), _q(th, 1.0, al, m), _c(th, 1.0, al, m)
    sphi = -al * np.cos(th) / (1 + al * np.sin(th) ** 2)
    ee = _f(e_closed_form(delta, th, alpha=al, mu=m))
    return _out(_f(phi0) + (-cp / qp + sphi / _sw(th, al) * (ee + pp / qp)) * _f(v0))  # eq expr


def iwc_time_scale(epsilon, theta0, delta, *, alpha=ALPHA, mu=MU):
    """Leading IWC duration epsilon ln(1/epsilon)/lambda_+ (eq TT, slow time)."""
    th, al, m = _check("Theorem 1", theta0, alpha, mu, delta=delta, epsilon=epsilon)
    epsilon = _f(epsilon)
    return _out(epsilon * np.log(1 / epsilon) / _lam(_p(th, 1.0, al, m), _f(delta))[0])  # eq TT


def w1_star(theta0, phi0, delta, *, alpha=ALPHA, mu=MU):
    """Separatrix w1* = -lambda_- b/p_+ < 0 of Theorem 2, eq w1star (w = eps w10 at y = 0)."""
    th, al, m = _check("Theorem 2", theta0, alpha, mu, phi0=phi0, bsign=+1, delta=delta)
    pp = _p(th, 1.0, al, m)
    lm = _lam(pp, _f(delta))[1]
    return _out(-lm * (-1.0 + _f(phi0) ** 2 * np.sin(th)) / pp)  # eq w1star


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
    """Raises HypothesisError, naming the hypothesis, unless Theorem 1 or 2 covers the Case."""
    if not (case.epsilon > 0 and np.isfinite(case.epsilon)):
        raise HypothesisError(f"epsilon must be > 0; got {case.epsilon}")
    theorem = theorem_of(case)
    check = check_theorem1 if theorem == 1 else check_theorem2
    check(case.theta0, case.phi0, case.v0, alpha=case.alpha, mu=case.mu, delta=case.delta)
    if theorem == 2 and not case.w10 < 0:
        raise HypothesisError(f"Theorem 2 starts the rod moving down, w10 < 0; got w10 = {case.w10}")


def _or_nan(formula):
    """formula(), or NaN where the hypotheses of the result it evaluates fail."""
    try:
        return float(formula())
    except (ValueError, ArithmeticError):
        return np.nan


@functools.lru_cache(maxsize=4096)
def predict(case):
    """The paper's predictions for a Case, NaN where a result's hypotheses fail (see
    check_case); computed once per case, since a sweep asks for each several times."""
    rod = dict(alpha=case.alpha, mu=case.mu)
    theorem = theorem_of(case)
    w1s = np.nan if theorem == 1 else _or_nan(lambda: w1_star(case.theta0, case.phi0, case.delta, **rod))
    return Prediction(theorem=theorem, e=_or_nan(lambda: e(case.delta, case.theta0, **rod)),
                      phi=_or_nan(lambda: phi_after_iwc(case.theta0, case.phi0, case.v0, case.delta, **rod)),
                      lambda_plus=_or_nan(lambda: lambda_pm(case.theta0, case.delta, **rod)[0]),
                      time_scale=_or_nan(lambda: iwc_time_scale(case.epsilon, case.theta0, case.delta, **rod)),
                      w1_star=w1s, iwc=None if theorem == 2 and np.isnan(w1s) else theorem == 1 or case.w10 < w1s)
