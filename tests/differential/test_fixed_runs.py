# SPDX-License-Identifier: BSD-2-Clause
"""The exact runs of the differential test's issue, each against the event-driven Filippov arm
(helpers.arm_filippov) or the rod's reference, with the FMUs run by fmpy directly
(helpers.differential): the reference is checked first (against the issue's figures, against the
older arm simulation of helpers.two_link_arm_iwc, against the theory's e), then the FMUs.

Bounds as in test_differential.py: 100 tol in each quantity's scale (1e-4 at the default tolerance)."""
import math

import numpy as np
import pytest

from helpers import arm_filippov as AF
from helpers import differential as D
from helpers.arm_lagrange import Arm, coefficients, floor_angle, rates
from helpers.two_link_arm_iwc import lift_off_ratio
from painleve.theory import general as G

ISSUE_ARM = dict(m1=0.6792496411080122, m2=0.4973322156252048, l1=0.9781579727614416, l2=0.7320502012458188,
                 J1=0.05415844293584162, J2=0.022209924133554094, g=9.81, mu=1.2847154189184387,
                 H=1.2532170162665548, k=4515325936.874412, c=51390.11230428312)
ISSUE_TH, ISSUE_OM = (-2.522633897557692, -1.213046821096188), (0.37055611557930906, 1.1516719700350075)

ME_ARM = dict(m1=1.6326542046112178, m2=0.394309392705803, l1=0.45767500646151, l2=0.43545691714067464,
              J1=0.02849885146040491, J2=0.006230835183553434, g=9.81, mu=1.363667984276838,
              H=0.7741396719910147, k=7916202593.971549, c=143763.6007668394)
ME_TH, ME_OM = (-2.1220861062384744, -1.0810473210092701), (1.1910741975642856, 1.3939064214246528)

DEFAULT_LIKE = dict(m1=1.0, m2=1.0, l1=0.5, l2=0.5, J1=0.25 / 12, J2=0.25 / 12, g=9.81, mu=0.8)
DEFAULT_TH = (-1.92, -1.40)

SI_ROD = dict(m=0.11075540715862829, l=0.06608815254978619, J=0.18743874722537796, g=82.84764506376017,
              k=6357327.019697341, c=4303.3608954933425, mu=3.3706875026659566)

INTERFACES = [("CS", None), ("CS", 1e-8), ("ME", 1e-8)]


def start_of(params, th, om):
    return dict(params, theta1=th[0], theta2=th[1], omega1=om[0], omega2=om[1])


def default_like(k, c):
    p, th, om = D.arm_on_floor(dict(DEFAULT_LIKE, k=k, c=c, H=1.0), *DEFAULT_TH)
    return p, th, om


def theory_e(params, th, om):
    arm = Arm(**{n: params[n] for n in ("H", "m1", "l1", "J1", "m2", "l2", "J2", "g", "mu")})
    co = G.Coefficients.of(coefficients(arm, np.asarray(th), np.asarray(om)))
    G.check(co, 1, delta=1.0, v0=1.0)
    M, L = params["m1"] + params["m2"], params["l1"] + params["l2"]
    eps, delta = math.sqrt(M * params["g"] / (params["k"] * L)), params["c"] / math.sqrt(M * params["k"])
    return G.e(delta, co), eps


def fmu_at(params, th, om, version, interface, tol, t, intervals=50):
    loaded = D.Loaded(D.fmu_path("TwoLinkArm", version))
    try:
        start = start_of(params, th, om)
        if interface == "CS":
            return loaded.cs(start, t, D.ARM_OUT + ("t_contact_end",), tolerance=tol)
        return loaded.me(start, t, D.ARM_OUT + ("t_contact_end",), rtol=tol, intervals=intervals)
    finally:
        loaded.close()


def arm_difference(out, run, params, v0=1.0):
    L = params["l1"] + params["l2"]
    scales = dict(v=v0, w=v0, theta1=1.0, theta2=1.0, omega1=v0 / L, omega2=v0 / L)
    return D.scaled_difference(out, D.arm_quantities(run), scales)


# ------------------------------------------------------------------------------------- the reference
def test_reference_reproduces_the_issue_run():
    """Tip on the floor, velocity (1, 0): contact, lift-off at t = 1.9089e-4 s with w = 0.046134 m/s."""
    assert AF.tip_height(ISSUE_ARM, ISSUE_TH) == pytest.approx(0.0, abs=1e-15)
    run = D.arm_reference(ISSUE_ARM, ISSUE_TH, ISSUE_OM)
    assert run.t_contact_end == pytest.approx(1.9089e-4, abs=5e-9)
    assert run.lift.w == pytest.approx(0.046134, abs=5e-7)
    assert run.events[-2:] == ["lift", "return"]


def test_reference_agrees_with_the_older_arm_simulation():
    """helpers.two_link_arm_iwc (numpy matrices, its own events) and arm_filippov (scalar math) on the
    theory test's arm, at eps = 1e-4, delta = 1: the same w/v0 at the return."""
    arm = Arm(H=0.3, mu=1.5)
    th = np.array([2.9, floor_angle(arm, 2.9, 1)])
    eps, delta, v0 = 1e-4, 1.0, 0.3
    ratio, old = lift_off_ratio(arm, th, v0, eps, delta)
    k = arm.M * arm.g / (arm.L * eps ** 2)
    p = dict(m1=arm.m1, m2=arm.m2, l1=arm.l1, l2=arm.l2, J1=arm.J1, J2=arm.J2, g=arm.g, mu=arm.mu, H=arm.H,
             k=k, c=delta * math.sqrt(arm.M * k))
    new = AF.simulate(p, th, rates(arm, th, v0, 0.0))
    assert new.w / v0 == pytest.approx(ratio, abs=1e-8)
    assert new.t == pytest.approx(old["t"], rel=1e-7)
    np.testing.assert_allclose(new.om, old["om"], atol=1e-7)


@pytest.mark.parametrize("k,c", [(3.924e11, 8.859e5), (3.924e13, 8.859e6)])
def test_reference_lift_off_tends_to_the_theory_e(k, c):
    """The default-like arm: w/v0 at lift-off within a few eps ln(1/eps) of e (0.06035 at the stiffer)."""
    p, th, om = default_like(k, c)
    e, eps = theory_e(p, th, om)
    if k > 1e13:
        assert e == pytest.approx(0.06035, abs=1e-5)
    run = D.arm_reference(p, th, om)
    assert abs(run.lift.w - e) < 10 * eps * math.log(1 / eps)


# ------------------------------------------------------------------------------------- the FMUs
@pytest.mark.parametrize("interface,tol", INTERFACES)
@pytest.mark.parametrize("version", D.VERSIONS)
def test_issue_arm_run(version, interface, tol):
    run = D.arm_reference(ISSUE_ARM, ISSUE_TH, ISSUE_OM)
    out = fmu_at(ISSUE_ARM, ISSUE_TH, ISSUE_OM, version, interface, tol, run.t)
    diff = arm_difference(out, run, ISSUE_ARM)
    assert diff <= D.bound_of(tol), (f"w {out['w']:.6g} (reference {run.w:.6g}), t_contact_end "
                                     f"{out['t_contact_end']:.6g} (reference {run.t_contact_end:.6g}), diff {diff:.3g}")


@pytest.mark.parametrize("interface,tol", INTERFACES)
@pytest.mark.parametrize("version", D.VERSIONS)
@pytest.mark.parametrize("k,c", [(3.924e11, 8.859e5), (3.924e13, 8.859e6)])
def test_default_like_arm_run(k, c, version, interface, tol):
    """The FMU's state at the reference's return, and its w/v0 there against e."""
    p, th, om = default_like(k, c)
    e, eps = theory_e(p, th, om)
    run = D.arm_reference(p, th, om)
    out = fmu_at(p, th, om, version, interface, tol, run.t)
    diff = arm_difference(out, run, p)
    assert diff <= D.bound_of(tol), f"w/v0 {out['w']:.6g} (reference {run.w:.6g}, e {e:.6g}), diff {diff:.3g}"
    assert abs(out["w"] - e) < 10 * eps * math.log(1 / eps)


@pytest.mark.parametrize("version", D.VERSIONS)
def test_me_outcome_does_not_depend_on_the_output_grid(version):
    """ME at rtol 1e-10 on two output grids (50 and 137 intervals): both at the reference to 100 tol."""
    run = D.arm_reference(ME_ARM, ME_TH, ME_OM)
    outs = [fmu_at(ME_ARM, ME_TH, ME_OM, version, "ME", 1e-10, run.t, intervals=n) for n in (50, 137)]
    diffs = [arm_difference(o, run, ME_ARM) for o in outs]
    assert max(diffs) <= D.bound_of(1e-10), (f"w {outs[0]['w']:.6g} / {outs[1]['w']:.6g} on the two grids, "
                                             f"reference {run.w:.6g}; diffs {diffs}")


@pytest.mark.parametrize("version", D.VERSIONS)
def test_si_rod_steps_are_all_ok(version):
    """PainleveRodSI in Co-Simulation from its default start, stepped by stopTime/60: every step OK
    (fmpy raises on a status worse than a warning), and the state finite throughout."""
    loaded = D.Loaded(D.fmu_path("PainleveRodSI", version))
    try:
        stop = loaded.md.defaultExperiment.stopTime
        stop = float(stop)
        seen = []
        loaded.cs(SI_ROD, stop, ("y",), steps=60,
                  every_step=lambda t, get: seen.append(get(["x", "v", "y", "w", "theta", "phi"])))
    finally:
        loaded.close()
    assert len(seen) == 60 and np.all(np.isfinite(seen))


# ------------------------------------------------------------------------------------- convergence in eps
EPS = (1e-4, 1e-5, 1e-6)
CONVERGENCE = [("CS", None), ("ME", 1e-8)]


@pytest.mark.parametrize("version", D.VERSIONS)
def test_arm_iwc_converges_to_e_in_both_interfaces(version):
    """The default-like arm (delta = 1) at eps = 1e-4, 1e-5, 1e-6: in CS (default tolerance) and ME
    (rtol 1e-8) the error of w/v0 at the return against e falls with eps (by 10 over the two decades,
    as the reference's does), and the two interfaces agree to 100 (tol_CS + tol_ME)."""
    M, L, g = 2.0, 1.0, 9.81
    errors = {i: [] for i in CONVERGENCE}
    for eps in EPS:
        k = M * g / (L * eps ** 2)
        p, th, om = default_like(k, math.sqrt(M * k))
        e, _ = theory_e(p, th, om)
        run = D.arm_reference(p, th, om)
        outs = {i: fmu_at(p, th, om, version, i[0], i[1], run.t) for i in CONVERGENCE}
        for i, out in outs.items():
            errors[i].append(abs(out["w"] - e))
        w_cs, w_me = (outs[i]["w"] for i in CONVERGENCE)
        assert abs(w_cs - w_me) <= 100 * (1e-6 + 1e-8), f"eps {eps:g}: CS w {w_cs:.6g}, ME w {w_me:.6g}"
    for i, err in errors.items():
        assert err[-1] < err[0] / 10, f"{i}: |w/v0 - e| = {err} at eps = {EPS}"


# ------------------------------------------------------------------------------------- the coefficients
@pytest.mark.parametrize("version", D.VERSIONS)
def test_arm_cases_start_in_the_paradox_by_the_fmus_own_outputs(version):
    """The random arm cases' start (tip on the floor, w = 0, v = 1 m/s, Theorem 1's quadrant by
    helpers.arm_lagrange): the FMU's outputs a, b, p_+-, q_+- there are the same numbers."""
    loaded = D.Loaded(D.fmu_path("TwoLinkArm", version))
    names = ("a", "b", "p_plus", "p_minus", "q_plus", "q_minus")
    try:
        for case in D.cases("TwoLinkArm", 8, 5):
            s = case.start
            arm = Arm(**{n: s[n] for n in ("H", "m1", "l1", "J1", "m2", "l2", "J2", "g", "mu")})
            th, om = np.array([s["theta1"], s["theta2"]]), np.array([s["omega1"], s["omega2"]])
            mine = coefficients(arm, th, om)
            assert mine["p_plus"] < 0 and mine["b"] < 0
            out = loaded.cs(s, 1e-12, names)
            for n in names:
                assert out[n] == pytest.approx(mine[n], rel=1e-6, abs=1e-9), n
    finally:
        loaded.close()
