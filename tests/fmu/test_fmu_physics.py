# SPDX-License-Identifier: BSD-2-Clause
"""The FMU's physics against laws and closed forms: free flight, energy,
quasi-static slipping, Filippov sticking, and impact without collision."""
from ctypes import POINTER, c_double

import numpy as np
import pytest

from helpers.raw_instances import Rod
from painleve.theory import analytic as an
from helpers.rod_sim import energy_gradient, event_count, mode_changes, phases, rod_energy, simulate


def test_free_flight_matches_closed_form(fmu_path):
    # Without contact the centre of mass falls freely and the rod spins uniformly.
    x0, v0, y0, w0, th0, ph0 = 0.2, 0.7, 2.0, 0.5, 0.3, 2.0
    r = simulate(fmu_path, 1.0, rtol=1e-12, output_interval=0.01,
                 x=x0, v=v0, y=y0, w=w0, theta=th0, phi=ph0)
    t = r["time"]
    theta = th0 + ph0 * t
    X0, Y0 = x0 - np.cos(th0), y0 + np.sin(th0)           # eq coord
    Xd, Yd = v0 + ph0 * np.sin(th0), w0 + ph0 * np.cos(th0)
    expected = {
        "theta": theta, "phi": np.full_like(t, ph0),
        "x": X0 + Xd * t + np.cos(theta), "y": Y0 + Yd * t - t**2 / 2 - np.sin(theta),
        "v": Xd - ph0 * np.sin(theta), "w": Yd - t - ph0 * np.cos(theta),
    }
    assert np.all(~r["contact"]) and np.all(r["F_N"] == 0)
    for name, value in expected.items():
        np.testing.assert_allclose(r[name], value, rtol=0, atol=1e-8, err_msg=name)


def test_energy_is_conserved_without_damping_and_friction(fmu_path):
    # delta = 0, mu = 0: a conservative spring contact; the rod bounces.
    r = simulate(fmu_path, 0.6, rtol=1e-10, output_interval=0.001,
                 mu=0, delta=0, epsilon=1e-2, y=0.05, w=-0.5, theta=1.0, phi=0.5, v=1.0)
    assert r["contact"].any() and not r["contact"][-1], "the rod must hit the floor and leave it"
    E = rod_energy(r, alpha=3, epsilon=1e-2, contact=r["contact"])
    np.testing.assert_allclose(r["energy"], E, rtol=1e-12, atol=1e-12)
    assert np.max(np.abs(E - E[0])) < 1e-6


@pytest.mark.parametrize("case", [
    dict(mu=3, delta=1, theta=1.0, phi=0.5, v=1.0),      # IWC (Theorem 1)
    dict(mu=1, delta=0.5, theta=0.3, phi=0.0, v=0.1),    # slip, stick, slip
    dict(mu=0.5, delta=0.2, y=0.05, w=-1.0, theta=1.2, phi=-1.0, v=-0.5),  # hit, bounce
])
def test_energy_never_increases_with_damping_and_friction(fmu_path, case):
    eps = 1e-3
    r = simulate(fmu_path, 0.5, rtol=1e-9, output_interval=1e-3, epsilon=eps, **case)
    E = rod_energy(r, alpha=3, epsilon=eps, contact=r["contact"])
    np.testing.assert_allclose(r["energy"], E, rtol=1e-12, atol=1e-12)
    assert r["contact"].any()
    assert np.max(np.diff(E)) < 1e-7 * np.max(np.abs(E))
    assert E[-1] < E[0]


def test_energy_is_constant_in_free_flight_after_a_damped_lift_off(fmu_path):
    # delta = 1: the end leaves the spring at y = -eps delta w < 0, where F_N = 0. The spring's
    # 0.5 (y/eps)^2 goes to the damper at that instant; above and below the floor the flight conserves E.
    eps = 1e-3
    r = simulate(fmu_path, 0.1, rtol=1e-10, output_interval=eps / 50, epsilon=eps, delta=1.0)
    last_contact = np.flatnonzero(r["contact"])[-1]
    flight = np.arange(last_contact + 1, len(r["time"]))
    assert np.any(r["y"][flight] < 0) and np.any(r["y"][flight] > 0), "the flight must start below the floor"
    E = r["energy"][flight]
    assert np.ptp(E) <= 1e-8 * abs(E[0])
    y_off = r["y"][last_contact + 1]                  # the lift-off event row (fmpy records it twice)
    released = r["energy"][last_contact] - E[0]
    assert released == pytest.approx(0.5 * (y_off / eps) ** 2, rel=1e-6)


CONSISTENT = dict(alpha=3, mu=1, delta=1, theta=0.3, phi=0.0, v=0.1, y=0.0, w=0.0)


@pytest.fixture(scope="module")
def consistent_runs(fmu_path):
    return {eps: simulate(fmu_path, 1.2, rtol=1e-8, output_interval=0.01, epsilon=eps, **CONSISTENT)
            for eps in (1e-2, 1e-3)}


def test_consistent_slip_stays_in_contact_at_the_quasi_static_force(consistent_runs):
    errors = []
    for eps, r in consistent_runs.items():
        assert an.quadrant(CONSISTENT["theta"], CONSISTENT["phi"], alpha=3, mu=1) == "slipping"
        slipping = (r["mode"] == 1) & (r["time"] > 0.05)       # after the O(eps) landing transient
        assert slipping.sum() > 10 and np.all(r["contact"])
        th, ph = r["theta"][slipping], r["phi"][slipping]
        quasi_static = -an.b(th, ph) / an.p_plus(th, alpha=3, mu=1)   # eq kk
        errors.append(np.max(np.abs(r["F_N"][slipping] - quasi_static)))
    assert errors[0] < 10 * 1e-2 and errors[1] < errors[0] / 10


def test_slip_decelerates_into_stick_with_v_exactly_zero(consistent_runs):
    r = consistent_runs[1e-3]
    assert phases(r)[:2] == [(True, 1), (True, 0)]
    v = r["v"]
    first_stick = np.argmax(r["mode"] == 0)
    assert np.all(np.diff(v[:first_stick]) <= 0), "v falls monotonically while slipping"
    assert np.all(v[r["mode"] == 0] == 0.0)
    assert event_count(r) <= 4


def test_stick_ends_at_the_fold_with_friction_inside_the_cone(consistent_runs):
    r = consistent_runs[1e-3]
    stick = r["mode"] == 0
    assert np.all(np.abs(r["F_T"][stick]) <= CONSISTENT["mu"] * r["F_N"][stick] * (1 + 1e-12))
    leave = [i for i in mode_changes(r) if r["mode"][i - 1] == 0][0]
    th, ph, F = r["theta"][leave - 1], r["phi"][leave - 1], r["F_N"][leave - 1]
    a = an.a(th, ph)
    q = an.q_minus(th, alpha=3, mu=1) if r["mode"][leave] == -1 else an.q_plus(th, alpha=3, mu=1)
    assert abs(a + q * F) < 1e-6 * abs(a), "stick must end where a + q F_N crosses 0 (Lemma lemma:nonStick)"


IWC = dict(alpha=3, mu=3, theta=1.0, phi=0.5, v=1.0, delta=1.0, epsilon=1e-4, y=0.0, w=0.0)


def return_to_floor(r):
    """The first row after lift-off at which the rod is back at y = 0."""
    left = np.flatnonzero(~r["contact"])[0]
    back = left + np.flatnonzero(r["y"][left:] >= 0)[0]
    return back


@pytest.mark.parametrize("solver, rtol, tolerance", [("CVode", 1e-6, 0.01), ("Euler", None, 0.05)])
def test_iwc_returns_with_w_equal_to_e_v0(fmu_path, solver, rtol, tolerance):
    p = IWC
    assert an.quadrant(p["theta"], p["phi"], alpha=3, mu=3) == "inconsistent"
    # fmpy's Euler steps once per output interval: the step is set through both.
    h = p["epsilon"] / 100
    kw = dict(rtol=rtol, output_interval=2e-4) if solver == "CVode" else dict(step_size=h, output_interval=h)
    r = simulate(fmu_path, 4e-3, solver=solver, **kw, **p)
    # compression, stick, the O(eps^2) slip at the fold (docs/model.md §2; shorter
    # than one Euler step, so Euler may take fold and lift-off in one event), flight
    seen = [ph for ph in phases(r) if ph != (True, -1)]
    assert seen[:3] == [(True, 1), (True, 0), (False, -1)]
    compression = r["mode"] == 1
    assert np.all(np.diff(r["v"][compression]) <= 0) and np.all(r["y"][compression] <= 0)
    assert np.all(r["v"][r["mode"] == 0] == 0.0)
    i = return_to_floor(r)
    e = an.e(p["delta"], p["theta"], alpha=3, mu=3)
    assert r["w"][i] > 0
    assert abs(r["w"][i] / p["v"] - e) < tolerance * e


# ------------------------------------------------------------- sticking energy
# The Theorem 1 default with delta = 0: compression, a stick of duration O(eps),
# the short backward slip at the fold, flight. Nothing dissipates while sticking.
STICK_NO_DAMPING = dict(alpha=3, mu=3, delta=0.0, theta=1.0, phi=0.5, v=1.0, y=0.0, w=0.0)


def test_energy_never_increases_through_a_stick_without_damping(fmu_path):
    # The exact Filippov field holds v' = 0 with the friction force F_T of docs/model.md §1, which
    # does no work (F_T v = 0): E is constant while sticking, falls while slipping, constant in
    # flight. Proposition lem:Filippov's leading-order field drops a and gains phi^3 sin cos.
    eps, rtol = 1e-3, 1e-9
    r = simulate(fmu_path, 0.02, rtol=rtol, output_interval=eps / 20, epsilon=eps, **STICK_NO_DAMPING)
    assert phases(r)[:2] == [(True, 1), (True, 0)] and not r["contact"][-1]
    stick = np.flatnonzero(r["mode"] == 0)
    assert len(stick) > 20, "the stick must be sampled densely"
    E = r["energy"]
    np.testing.assert_allclose(E, rod_energy(r, alpha=3, epsilon=eps, contact=r["contact"]), rtol=1e-12, atol=1e-12)
    bound = 10 * rtol * np.max(np.abs(E))
    assert np.max(np.diff(E)) <= bound, f"energy rises by {np.max(np.diff(E)):.3g} in one sample"
    assert abs(E[stick[-1]] - E[stick[0]]) <= bound, "no work is done while sticking"
    assert E[-1] < E[0] - 0.1                                # friction takes its share while slipping


@pytest.mark.parametrize("delta", [0.0, 1.0])
@pytest.mark.parametrize("theta", [0.7, 1.0, 1.3, 2.0])
@pytest.mark.parametrize("phi", [-0.8, 0.5, 1.2])
def test_sticking_derivatives_dissipate_only_in_the_damper(loaded, delta, theta, phi):
    # Pointwise, from fmi2GetDerivatives: dE/dt = F_N w - F_T v + d(spring)/dt = -delta w^2/eps
    # with v = 0 (the spring's rate y w/eps^2 cancels the elastic part of F_N w).
    alpha, eps = 3.0, 1e-3
    for w in (-2e-4, 0.0, 2e-4):
        rod = Rod(loaded)
        rod.initialize(alpha=alpha, mu=3.0, delta=delta, epsilon=eps, x=0.0, v=0.0, y=-1e-6, w=w,
                       theta=theta, phi=phi)
        assert (bool(rod.fmu.getBoolean([rod.vr["contact"]])[0]), rod.fmu.getInteger([rod.vr["mode"]])[0]) \
            == (True, 0), "the state must stick"
        x, dx = rod.x.copy(), np.zeros(6)
        rod.fmu.getDerivatives(dx.ctypes.data_as(POINTER(c_double)), 6)
        assert dx[1] == 0.0
        grad = energy_gradient(x, alpha, eps, contact=True)
        rate, damper = grad @ dx, -delta * x[3] ** 2 / eps
        scale = np.abs(grad) @ np.abs(dx)                   # round-off of the sum is ~1e-16 of this
        rod.free()
        assert abs(rate - damper) <= 1e-13 * scale, (rate, damper, scale)
