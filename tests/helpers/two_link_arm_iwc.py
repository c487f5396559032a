# SPDX-License-Identifier: BSD-2-Clause
"""Direct simulation of the compliant two-link arm (helpers.arm_lagrange) through an impact
without collision, by its own equations of motion in (theta, omega): no coefficient of eq Painleve,
no Filippov formula, no phase the theory predicts is assumed.

Contact: F_N = k(-y) - c w while in contact (entered at y = 0 going down, left where that force
reaches 0), linear (kappa = beta = 0), k = M g/(L eps^2), c = delta sqrt(M k) (the FMU's scaling).
Friction: Coulomb at the tip. Slipping (s = +-1), the tangential force on the arm is -s mu F_N;
sticking (v = 0), it is the value -F_T that keeps v' = 0 (solved with omega' from the mass matrix
and the constraint), and sticking ends where |F_T| reaches mu F_N. Each mode is integrated with
DOP853 to the events that end it; the state is (theta - theta0, omega) so that tolerances on the
angles can be of the order eps^2 L the initial layer needs."""
import numpy as np
import scipy.integrate

from .arm_lagrange import applied, jacobian, mass_matrix, tip, velocity_products


def _accel(arm, th, om, fn, s, k_t=None):
    """(omega', F_T) in mode s for normal force fn; s = 0 solves F_T from v' = 0."""
    J, M = jacobian(arm, th), mass_matrix(arm, th)
    rhs = applied(arm, th, om) + J[1] * fn
    if s != 0:
        ft = s * arm.mu * fn
        return np.linalg.solve(M, rhs - J[0] * ft), ft
    A = np.block([[M, J[0][:, None]], [J[0][None, :], np.zeros((1, 1))]])
    sol = np.linalg.solve(A, np.concatenate([rhs, [-velocity_products(arm, th, om)[0]]]))
    return sol[:2], sol[2]


def simulate(arm, th0, om0, eps, delta, t_max=None, rtol=1e-11, max_phases=60):
    """From (th0, om0) with the tip at y = 0 moving down or along the floor, simulate until the tip
    is back at y = 0 after contact; returns dict(t, th, om, v, w, phases) there."""
    k = arm.M * arm.g / (arm.L * eps ** 2)
    c = delta * np.sqrt(arm.M * k)
    th0 = np.asarray(th0, float)
    T = np.sqrt(arm.L / arm.g)
    t_max = t_max or 50 * eps * np.log(1 / eps) * T + 10 * eps * T
    atol = np.array([1e-9 * eps ** 2, 1e-9 * eps ** 2, 1e-10 * eps / T, 1e-10 * eps / T])

    def state(z):
        th, om = th0 + z[:2], z[2:]
        (x, y), (v, w) = tip(arm, th), jacobian(arm, th) @ om
        return th, om, y, v, w

    def force(z):
        th, om, y, v, w = state(z)
        return -k * y - c * w

    with np.errstate(over="ignore", invalid="ignore"):  # DOP853's rejected trial steps may overflow
        return _phases(arm, th0, om0, t_max, rtol, atol, max_phases, state, force)


def _phases(arm, th0, om0, t_max, rtol, atol, max_phases, state, force):
    z, t, contact, s, phases = np.concatenate([[0.0, 0.0], om0]), 0.0, True, 1, []
    for _ in range(max_phases):
        def rhs(t, z, contact=contact, s=s):
            th, om = th0 + z[:2], z[2:]
            fn = force(z) if contact else 0.0
            return np.concatenate([om, _accel(arm, th, om, fn, s if contact else 1)[0]])
        events = []
        if contact:
            events.append(("lift", lambda t, z: force(z), -1))
            if s != 0:
                events.append(("v=0", lambda t, z: state(z)[3], -s))
            else:
                ft = lambda z: _accel(arm, state(z)[0], state(z)[1], force(z), 0)[1]  # noqa: E731
                events.append(("slip+", lambda t, z: ft(z) - arm.mu * force(z), 1))
                events.append(("slip-", lambda t, z: ft(z) + arm.mu * force(z), -1))
        else:
            events.append(("return", lambda t, z: state(z)[2], 1))
            events.append(("touch", lambda t, z: state(z)[2], -1))
        fns = []
        for name, f, direction in events:
            f.terminal, f.direction = True, direction
            fns.append(f)
        sol = scipy.integrate.solve_ivp(rhs, (t, t_max), z, method="DOP853", rtol=rtol, atol=atol, events=fns)
        hits = [(sol.t_events[i][0], i) for i in range(len(fns)) if len(sol.t_events[i])]
        if not hits:
            raise RuntimeError(f"no event before t_max = {t_max}; phases {phases}")
        t, i = min(hits)
        z = sol.y_events[i][0]
        name = events[i][0]
        phases.append((name, t))
        if name == "return":
            th, om, y, v, w = state(z)
            return dict(t=t, th=th, om=om, v=v, w=w, phases=phases)
        if name == "lift":
            contact = False
        elif name == "touch":
            contact, s = True, (1 if state(z)[3] > 0 else -1)
        elif name == "v=0":
            th, om = state(z)[:2]
            fn = force(z)
            ft = _accel(arm, th, om, fn, 0)[1]
            if abs(ft) < arm.mu * fn:   # Coulomb can hold the tip: stick, v set to exactly 0
                minv = np.linalg.inv(mass_matrix(arm, th))
                wt = jacobian(arm, th)[0]
                z = np.concatenate([z[:2], om - minv @ wt * (wt @ om) / (wt @ minv @ wt)])
                s = 0
            else:
                s = -s
        else:
            s = 1 if name == "slip+" else -1
    raise RuntimeError(f"more than {max_phases} phases: {phases}")


def lift_off_ratio(arm, th0, v0, eps, delta):
    """Simulated w/v0 at the return to y = 0, from the tip on the floor with velocity (v0, 0)."""
    om0 = np.linalg.solve(jacobian(arm, np.asarray(th0, float)), [v0, 0.0])
    out = simulate(arm, th0, om0, eps, delta)
    return out["w"] / v0, out

