# SPDX-License-Identifier: BSD-2-Clause
"""The paper's formulas written out again for the tests of painleve.theory.analytic
(tests/theory/test_analytic*.py), independent of the module: eq coeffs and eq Sw,
the positive root of eq lambdapm2, the Painleve wedge found by bracketing."""
import numpy as np
import scipy.optimize

CASES = [(3.0, 3.0), (3.0, 1.4), (2.0, 3.0)]  # (alpha, mu) with a Painleve wedge


def coef(theta, alpha, mu):
    """The paper's eq coeffs and eq Sw, written out again."""
    s, c = np.sin(theta), np.cos(theta)
    d = dict(qp=alpha * s * c - mu * (1 + alpha * s * s), qm=alpha * s * c + mu * (1 + alpha * s * s),
             pp=1 + alpha * c * c - mu * alpha * s * c, pm=1 + alpha * c * c + mu * alpha * s * c,
             cp=-alpha * (c - mu * s), cm=-alpha * (c + mu * s))
    with np.errstate(invalid="ignore", divide="ignore"):  # 0/0 when mu = 0
        d["Sw"] = (d["qm"] * d["pp"] - d["qp"] * d["pm"]) / (d["qm"] - d["qp"])  # general form of eq Sw
        d["Sphi"] = (d["qm"] * d["cp"] - d["qp"] * d["cm"]) / (d["qm"] - d["qp"])
    return d


def lam_plus(p, delta):
    """Positive root of lambda^2 + delta p lambda + p = 0 (eq lambdapm2), via numpy.roots."""
    return max(np.roots([1.0, delta * p, p]).real)


def wedge(alpha, mu):
    """Zeros of p_+ on (0, pi/2) found by bracketing, independent of eq thetacrit."""
    pp = lambda t: coef(t, alpha, mu)["pp"]  # noqa: E731
    tmin = scipy.optimize.minimize_scalar(pp, bounds=(0.01, 1.56), method="bounded").x
    return (scipy.optimize.brentq(pp, 1e-6, tmin, xtol=1e-15),
            scipy.optimize.brentq(pp, tmin, np.pi / 2 - 1e-9, xtol=1e-15))


def interior(alpha, mu, n):
    t1, t2 = wedge(alpha, mu)
    return np.linspace(t1, t2, n + 2)[1:-1]


def slope(x, y):
    return np.polyfit(np.log(x), np.log(y), 1)[0]
