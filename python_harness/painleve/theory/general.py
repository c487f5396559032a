# SPDX-License-Identifier: BSD-2-Clause
"""The paper's results for any body (Hogan & Kristiansen, remark after eq Sw): everything from the
coefficients of eq Painleve at the start state, never from the body's geometry.

A body whose contact point slips with speed v and leaves the floor with speed w obeys, in the
paper's scaled form, v' = a + q_s F_N and w' = b + p_s F_N for slip s = sign(v) (eq Painleve);
while it sticks, w' = b + S_w F_N + O(1) with S_w the Filippov combination of eq Sw. The rod
(rod_coefficients) is one such body; the two-link arm (TwoLinkArm) another (docs/general_body.md,
"The theory for d = 2"). Given (a, b, p_+-, q_+-, S_w) and delta this module gives:

* the fast eigenvalues lambda_pm (eq lambdapm), the end of slipping compression (eq initStick);
* e(delta) by the closed form eq eGeneral and by integrating the stick system (eq stickEps0),
  its asymptotes eq eDeltaLarge, eq eDeltaSmall and its delta = 0 value (the leading term of eq
  eDeltaSmall, which is eq eDeltaZero for the rod);
* Theorem 2's separatrix w1* (eq w1star), the quadrant of figure fig:GB, the paradox test p_+ < 0;
* the jump of the generalized velocities over the IWC (Theorem 1's phi, for vectors c_+, S_phi).

All functions broadcast over numpy arrays; scalar input gives float output. Hypotheses that
fail raise HypothesisError naming them."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg
import scipy.optimize

from .hypotheses import HypothesisError, Hypotheses, as_result, floats, fmt

NAMES = ("a", "b", "p_plus", "p_minus", "q_plus", "q_minus", "S_w")


@dataclass(frozen=True)
class Coefficients:
    """eq Painleve's coefficients at one state (or arrays of states), scaled as the paper scales.

    S_w: the Filippov stick value; None takes eq Sw's combination of p_+- and q_+-."""
    a: object
    b: object
    p_plus: object
    p_minus: object
    q_plus: object
    q_minus: object
    S_w: object = None

    def __post_init__(self):
        for name in NAMES[:-1]:
            object.__setattr__(self, name, floats(getattr(self, name)))
        if self.S_w is None:
            object.__setattr__(self, "S_w", filippov_S_w(self))
        object.__setattr__(self, "S_w", floats(self.S_w))

    @classmethod
    def of(cls, values):
        """From a mapping holding the names of NAMES (an FMU's outputs, say); S_w may be missing."""
        return cls(*(values[n] for n in NAMES[:-1]), S_w=values.get("S_w"))


def filippov_S_w(co):
    """S_w = (q_- p_+ - q_+ p_-)/(q_- - q_+), eq Sw: w' per unit F_N of the Filippov field."""
    return as_result((co.q_minus * co.p_plus - co.q_plus * co.p_minus) / (co.q_minus - co.q_plus))  # eq Sw


def filippov_combination(co, c_plus, c_minus):
    """S_phi = (q_- c_+ - q_+ c_-)/(q_- - q_+), eq Sw, for any generalized-velocity response c_+- (vectors too)."""
    return (co.q_minus * floats(c_plus) - co.q_plus * floats(c_minus)) / (co.q_minus - co.q_plus)


# ----------------------------------------------------------------- hypotheses
def check(co, theorem=1, *, delta=None, v0=None):
    """Raise HypothesisError unless Theorem 1 (b < 0) or 2 (b > 0) covers the coefficients:
    p_+ < 0, q_+ < 0 < q_-, a != 0 and the sign of b (with delta >= 0, v0 > 0 if given)."""
    who = f"Theorem {theorem}"
    h = Hypotheses(who, co.a, co.b, co.p_plus, co.q_plus, co.q_minus, delta, v0)
    h.scalar("delta", delta, lambda x: x >= 0, "delta >= 0")
    h.scalar("v0", v0, lambda x: x > 0, "v0 > 0")
    pp, qp, qm, aa, bb = (h.bc(x) for x in (co.p_plus, co.q_plus, co.q_minus, co.a, co.b))
    h.need(pp < 0, "p_+ < 0", lambda i: f"p_+ = {fmt(pp.ravel()[i])}")
    h.need((qp < 0) & (qm > 0), "q_+ < 0 < q_-", lambda i: f"q_+ = {fmt(qp.ravel()[i])}, q_- = {fmt(qm.ravel()[i])}")
    h.need(aa != 0, "a != 0", lambda i: f"a = {fmt(aa.ravel()[i])}")
    if theorem == 1:
        h.need(bb < 0, "b < 0", lambda i: f"b = {fmt(bb.ravel()[i])}")
    else:
        h.need(bb > 0, "b > 0", lambda i: f"b = {fmt(bb.ravel()[i])}")
    h.done()


def theorem_of(co):
    """1 where b < 0 (inconsistent), 2 where b > 0 (indeterminate)."""
    return as_result(np.where(co.b < 0, 1, 2))


def paradox(co):
    """True where the body is in the Painleve paradox for forward slip: p_+ < 0."""
    return as_result(co.p_plus < 0)


def quadrant(co):
    """The quadrant of figure fig:GB: "indeterminate" (b > 0, p_+ < 0), "lift-off" (b > 0, p_+ >= 0),
    "slipping" (b <= 0, p_+ >= 0), "inconsistent" (b <= 0, p_+ < 0)."""
    up, neg = np.broadcast_arrays(co.b > 0, co.p_plus < 0)
    names = np.array([["slipping", "inconsistent"], ["lift-off", "indeterminate"]])
    return as_result(names[up.astype(int), neg.astype(int)])


# ---------------------------------------------------------------- Theorem 1
def lambdas(p, delta):
    """(lambda_+, lambda_-) of lambda^2 + delta p lambda + p = 0 (eq lambdapm), p < 0, unchecked;
    lambda_- = p/lambda_+ avoids cancellation."""
    p, delta = floats(p), floats(delta)
    lp = -delta * p / 2 + np.sqrt(delta ** 2 * p ** 2 - 4 * p) / 2  # eq lambdapm
    return lp, p / lp


def lambda_pm(co, delta):
    """Fast eigenvalues (lambda_+, lambda_-) of compressed forward slip, eq lambdapm (needs p_+ < 0)."""
    h = Hypotheses("lambda_pm (eq lambdapm)", co.p_plus, delta)
    h.scalar("delta", delta, lambda x: x >= 0, "delta >= 0")
    h.need(h.bc(co.p_plus) < 0, "p_+ < 0", lambda i: f"p_+ = {fmt(h.bc(co.p_plus).ravel()[i])}")
    h.done()
    lp, lm = lambdas(co.p_plus, delta)
    return as_result(lp), as_result(lm)


def stick_start(co, delta, v0=1.0):
    """(yhat, w) where slipping compression ends (v = 0), eq initStick: w = -p_+ v0/q_+, yhat = w/lambda_+."""
    _check_e(co, delta)
    if not np.all(floats(v0) > 0):
        raise HypothesisError(f"Theorem 1 needs v0 > 0; got v0 = {v0}", ["v0 > 0"])
    w = -co.p_plus * floats(v0) / co.q_plus  # eq initStick
    return as_result(w / lambdas(co.p_plus, delta)[0]), as_result(w)


def xi_tau(delta, sw, lp):
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


def e_of(delta, pp, qp, sw):
    """eq eGeneral from (p_+, q_+, S_w) as float arrays, unchecked (analytic's rod path shares it)."""
    delta, pp, qp, sw = np.broadcast_arrays(floats(delta), pp, qp, sw)
    lp = lambdas(pp, delta)[0]
    xip, xim, tau = xi_tau(delta, sw, lp)
    return ((xip / xim) * (lp - xim) * pp / (qp * lp) * np.exp(xip * tau)).real  # eq eGeneral


def e(delta, co):
    """e(delta) = w/v0 at the return to y = 0 after IWC, eq eGeneral (Theorem 1's hypotheses but the
    sign of b, which e does not depend on)."""
    _check_e(co, delta)
    return as_result(e_of(delta, co.p_plus, co.q_plus, co.S_w))


def _check_e(co, delta):
    h = Hypotheses("e (eq eGeneral)", co.p_plus, co.q_plus, co.q_minus, delta)
    h.scalar("delta", delta, lambda x: x >= 0, "delta >= 0")
    pp, qp, qm = (h.bc(x) for x in (co.p_plus, co.q_plus, co.q_minus))
    h.need(pp < 0, "p_+ < 0", lambda i: f"p_+ = {fmt(pp.ravel()[i])}")
    h.need((qp < 0) & (qm > 0), "q_+ < 0 < q_-", lambda i: f"q_+ = {fmt(qp.ravel()[i])}, q_- = {fmt(qm.ravel()[i])}")
    h.need(h.bc(co.S_w) > 0, "S_w > 0", lambda i: f"S_w = {fmt(h.bc(co.S_w).ravel()[i])}")
    h.done()


def e_integrated_one(delta, pp, qp, sw):
    """e by exact integration of eq stickEps0 (yhat' = w, w' = S_w(-yhat - delta w)) from eq initStick
    (v0 = 1) to the first root of yhat + delta w: matrix exponential, bracket, brentq."""
    lp = lambdas(pp, delta)[0]
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


def e_integrated(delta, co):
    """e(delta) by integrating the stick system (e_integrated_one), state by state."""
    _check_e(co, delta)
    args = np.broadcast_arrays(floats(delta), co.p_plus, co.q_plus, co.S_w)
    out = np.array([e_integrated_one(*x) for x in zip(*(a.ravel() for a in args))]).reshape(args[0].shape)
    return as_result(out)


def e_large_delta(delta, co):
    """Leading term of e for delta >> 1, eq eDeltaLarge."""
    _check_e(co, delta)
    return as_result((co.p_minus - co.p_plus) / (co.q_minus * co.p_plus - co.q_plus * co.p_minus)
                     * floats(delta) ** -2.0)  # eq eDeltaLarge


def e_zero(co):
    """e(0) = sqrt(p_+(p_- - p_+)/(q_+(q_- - q_+))), the leading term of eq eDeltaSmall."""
    _check_e(co, 0.0)
    return as_result(np.sqrt(co.p_plus * (co.p_minus - co.p_plus) / (co.q_plus * (co.q_minus - co.q_plus))))


def e_small_delta(delta, co):
    """Two-term expansion of e for delta << 1, eq eDeltaSmall (error O(delta^2))."""
    e0 = floats(e_zero(co))
    slope = np.sqrt(co.S_w) / 2 * (np.pi - np.arctan(np.sqrt(-co.S_w / co.p_plus)))  # eq eDeltaSmall
    return as_result(e0 * (1 - slope * floats(delta)))


def velocity_jump(delta, co, c_plus, S_phi, v0=1.0, e_value=None):
    """Change of any generalized velocity over the IWC (Theorem 1's phi, eq expr), for c_+ and
    S_phi that may be vectors (last axis: the coordinates): {-c_+/q_+ + (S_phi/S_w)(e + p_+/q_+)} v0.
    The impulse of F_N over slipping compression is -v0/q_+ and over the stick (e + p_+/q_+) v0/S_w."""
    ee = floats(e(delta, co) if e_value is None else e_value)
    k1 = -1.0 / co.q_plus
    k2 = (ee + co.p_plus / co.q_plus) / co.S_w
    return (np.expand_dims(k1, -1) * floats(c_plus) + np.expand_dims(k2, -1) * floats(S_phi)) * floats(v0)


def iwc_time_scale(epsilon, delta, co):
    """Leading IWC duration eps ln(1/eps)/lambda_+ (eq TT), in the paper's scaled time."""
    epsilon = floats(epsilon)
    return as_result(epsilon * np.log(1 / epsilon) / floats(lambda_pm(co, delta)[0]))  # eq TT


def w1_star(delta, co):
    """Theorem 2's separatrix w1* = -lambda_- b/p_+ < 0 (eq w1star): IWC for w = eps w10 with w10 < w1*."""
    check(co, 2, delta=delta)
    return as_result(-lambdas(co.p_plus, delta)[1] * co.b / co.p_plus)  # eq w1star
