# SPDX-License-Identifier: BSD-2-Clause
"""ShakerTable's physics for its tests (tests/coupling/test_shaker_table*.py): the defaults of
its model description, both interfaces, a start with a transient, and the closed-form solution
of the forced damped oscillator M z'' + C z' + K z = F0 sin(2 pi f t) - F_N (piecewise in a
load that jumps)."""
import numpy as np

# The defaults of the spec (fmu_src/models/ShakerTable/modelDescription.xml start values).
DEFAULTS = dict(M=10.0, K=4e4, C=40.0, F0=50.0, frequency=5.0, belt_speed=0.0)
INTERFACES = ["ModelExchange", "CoSimulation"]
START = dict(position=1e-3, velocity=-0.02)   # a transient on top of the forced motion


def closed_form(t, t0=0.0, z0=0.0, v0=0.0, F_N=0.0, M=10.0, K=4e4, C=40.0, F0=50.0, frequency=5.0, **_):
    """z(t), z'(t) of M z'' + C z' + K z = F0 sin(W t) - F_N from z(t0) = z0, z'(t0) = v0
    (underdamped: C^2 < 4 K M): the particular solution A sin Wt + B cos Wt - F_N/K plus the
    damped free oscillation e^(-s tau) (c1 cos wd tau + c2 sin wd tau), tau = t - t0."""
    t = np.asarray(t, dtype=float)
    W = 2 * np.pi * frequency
    k, c = K - M * W**2, C * W
    A, B = F0 * k / (k * k + c * c), -F0 * c / (k * k + c * c)

    def particular(s):
        return A * np.sin(W * s) + B * np.cos(W * s) - F_N / K, W * (A * np.cos(W * s) - B * np.sin(W * s))
    s, wd = C / (2 * M), np.sqrt(K / M - (C / (2 * M))**2)
    zp0, vp0 = particular(t0)
    c1 = z0 - zp0
    c2 = (v0 - vp0 + s * c1) / wd
    tau = t - t0
    decay = np.exp(-s * tau)
    zp, vp = particular(t)
    z = zp + decay * (c1 * np.cos(wd * tau) + c2 * np.sin(wd * tau))
    v = vp + decay * ((wd * c2 - s * c1) * np.cos(wd * tau) - (s * c2 + wd * c1) * np.sin(wd * tau))
    return z, v


def piecewise_closed_form(t, jumps, z0=0.0, v0=0.0, **params):
    """The closed form under a load F_N that is jumps[i][1] from jumps[i][0] on (jumps[0][0] the
    start): each piece starts from where the last one ended."""
    t = np.asarray(t, dtype=float)
    z, v = np.empty_like(t), np.empty_like(t)
    ends = [tj for tj, _ in jumps[1:]] + [np.inf]
    for (t0, F_N), t1 in zip(jumps, ends):
        inside = (t >= t0) & (t < t1) if np.isfinite(t1) else t >= t0
        z[inside], v[inside] = closed_form(t[inside], t0, z0, v0, F_N, **params)
        if np.isfinite(t1):
            (z0,), (v0,) = closed_form([t1], t0, z0, v0, F_N, **params)
    return z, v
