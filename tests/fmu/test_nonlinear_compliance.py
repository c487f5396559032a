# SPDX-License-Identifier: BSD-2-Clause
"""The FMU with a nonlinear compliance law: h(yh, w) = -yh + kappa d^2 - delta w (1 + beta d),
d = max(-y/eps, 0), kappa a stiffening spring, beta a damping growing with penetration.

- Theorem 1 on the FMU converges, as eps -> 0, to the rigid limit computed for that law
  (painleve.theory.rigid_limit), not to the paper's linear e.
- Energy with the nonlinear spring's potential: conserved without damping and friction,
  never increasing with them.
- Laws that make h increase with y or w are refused, naming the parameter.
- Theorem 2's separatrix w1* moves by O(eps) only (the initial layer sees h's linear part).
"""
from dataclasses import dataclass

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

from painleve.theory import analytic as an
from painleve.theory import rigid_limit as rl
from painleve.experiments.acceptance import power_rate
from painleve.experiments.case import Case
from painleve.fmu.experiment import Experiment
from painleve.experiments.studies import convergence, separatrix
from helpers.raw_instances import Rod
from helpers.rod_sim import simulate


@dataclass(frozen=True)
class LawCase(Case):
    """A Case (its kappa and beta the FMU's start values) with the limits computed here."""

    @property
    def e_linear(self):
        """The paper's e (the linear law's closed form)."""
        return float(an.e(self.delta, self.theta0, alpha=self.alpha, mu=self.mu))

    @property
    def e_law(self):
        return float(rl.e(self.delta, self.theta0, kappa=self.kappa, beta=self.beta, v0=self.v0, alpha=self.alpha,
                          mu=self.mu))

    @property
    def phi_law(self):
        """Theorem 1's phi limit with the law's e: the same F_N drives phi and w in each phase."""
        th, kw = self.theta0, dict(alpha=self.alpha, mu=self.mu)
        pp, qp, cp = an.p_plus(th, **kw), an.q_plus(th, **kw), an.c_plus(th, **kw)
        ratio = an.S_phi(th, alpha=self.alpha) / an.S_w(th, alpha=self.alpha)
        return self.phi0 + (-cp / qp + ratio * (self.e_law + pp / qp)) * self.v0


LAWS = {"stiffening": dict(kappa=2.0), "hunt-crossley": dict(beta=2.0), "both": dict(kappa=2.0, beta=2.0)}
CASES = [dict(theta0=0.7, delta=0.5), dict(theta0=1.1, delta=2.0), dict(theta0=0.9, delta=1.0, v0=2.0)]
EPSILONS = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7]


@pytest.fixture(scope="module")
def experiment(fmu_path):
    with Experiment(fmu_path) as ex:
        yield ex


def table(outcomes, case):
    rows = [f"e (law) = {case.e_law:.10f}, e (linear) = {case.e_linear:.10f}",
            f"{'eps':>8} {'w/v0':>14} {'w/v0 - e law':>13} {'w/v0 - e lin':>13} {'phi - law':>11}"]
    rows += [f"{o.case.epsilon:8.0e} {o.w / case.v0:14.10f} {o.w / case.v0 - case.e_law:13.3e} "
             f"{o.w / case.v0 - case.e_linear:13.3e} {o.phi - case.phi_law:11.3e}" for o in outcomes]
    eps = np.array([o.case.epsilon for o in outcomes])
    rows.append(f"rates (log-log slope): w {power_rate(eps, [o.w / case.v0 - case.e_law for o in outcomes]):.3f}, "
                f"phi {power_rate(eps, [o.phi - case.phi_law for o in outcomes]):.3f}")
    return "\n".join(rows)


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("where", CASES)
def test_theorem1_converges_to_the_laws_e_not_the_linear_one(experiment, law, where):
    case = LawCase(phi0=0.5, **where, **LAWS[law])
    assert an.quadrant(case.theta0, case.phi0, alpha=case.alpha, mu=case.mu) == "inconsistent"
    epsilons = [eps for eps in EPSILONS if eps * (1 + case.delta) ** 3 <= 2e-2]   # the asymptotic regime
    outcomes = convergence(experiment, case, epsilons).outcomes
    text = table(outcomes, case)
    print(f"\n{law}, theta0 = {case.theta0}, delta = {case.delta}, v0 = {case.v0}\n{text}")
    assert all(o.iwc for o in outcomes), text
    err = np.array([o.w / case.v0 - case.e_law for o in outcomes])
    phi_err = np.array([o.phi - case.phi_law for o in outcomes])
    assert np.all(np.diff(np.abs(err)) < 0) and np.all(np.diff(np.abs(phi_err)) < 0), text
    # about eps ln(1/eps): a log-log slope a little under 1
    assert power_rate(np.array(epsilons), err) > 0.8, text
    assert power_rate(np.array(epsilons), phi_err) > 0.8, text
    assert abs(err[-1]) < 1e-5 * case.e_law, text
    # ... and the linear law's e is not the limit: it is off by far more than the error
    off = abs(case.e_law - case.e_linear)
    assert off > 1e-2 * case.e_linear and off > 1000 * abs(err[-1]), text
    assert all(abs(o.w / case.v0 - case.e_linear) > 0.5 * off for o in outcomes[1:]), text


@pytest.mark.parametrize("law", LAWS)
def test_co_simulation_reaches_the_laws_e_too(fmu_path, law):
    case = LawCase(theta0=0.9, phi0=0.5, delta=1.0, epsilon=1e-6, **LAWS[law])
    with Experiment(fmu_path, fmi_type="CoSimulation") as ex:
        o = ex.run(case)
    assert o.iwc
    assert o.w / case.v0 == pytest.approx(case.e_law, rel=1e-4)
    assert abs(o.w / case.v0 - case.e_linear) > 0.01 * case.e_linear


def spring_energy(y, eps, kappa):
    """The law's spring potential: the integral of its force d + kappa d^2 over d = -y/eps."""
    d = -y / eps
    return 0.5 * d**2 + kappa * np.maximum(d, 0.0) ** 3 / 3


def energy(r, eps, kappa, alpha=3.0):
    """Energy from the states alone: centre of mass (x - cos theta, y + sin theta), inertia 1/alpha,
    the spring's potential where its force acts."""
    s, c, phi, y = np.sin(r["theta"]), np.cos(r["theta"]), r["phi"], r["y"]
    kinetic = 0.5 * ((r["v"] + phi * s) ** 2 + (r["w"] + phi * c) ** 2) + 0.5 * phi**2 / alpha
    return kinetic + (y + s) + np.where(r["contact"], spring_energy(y, eps, kappa), 0.0)


@pytest.mark.parametrize("law", [dict(kappa=5.0), dict(kappa=5.0, beta=3.0), dict(kappa=40.0)])
def test_energy_is_conserved_without_damping_and_friction(fmu_path, law):
    # delta = 0, mu = 0: a conservative, stiffening spring (beta multiplies delta: no damping)
    eps = 1e-2
    r = simulate(fmu_path, 0.6, rtol=1e-10, output_interval=0.001, mu=0, delta=0, epsilon=eps, y=0.05, w=-0.5,
                 theta=1.0, phi=0.5, v=1.0, **law)
    assert r["contact"].any() and not r["contact"][-1], "the rod must hit the floor and leave it"
    E = energy(r, eps, law["kappa"])
    np.testing.assert_allclose(r["energy"], E, rtol=1e-12, atol=1e-12)
    assert np.max(np.abs(E - E[0])) < 1e-6
    # the cubic term matters: without it the energy would not be conserved
    linear = energy(r, eps, 0.0)
    assert np.max(np.abs(linear - linear[0])) > 1e-3


@pytest.mark.parametrize("law", [dict(kappa=3.0), dict(beta=3.0), dict(kappa=3.0, beta=10.0)])
@pytest.mark.parametrize("case", [
    dict(mu=3, delta=1, theta=1.0, phi=0.5, v=1.0),      # IWC (Theorem 1)
    dict(mu=1, delta=0.5, theta=0.3, phi=0.0, v=0.1),    # slip, stick, slip
    dict(mu=0.5, delta=0.2, y=0.05, w=-1.0, theta=1.2, phi=-1.0, v=-0.5),  # hit, bounce
])
def test_energy_never_increases_with_damping_and_friction(fmu_path, case, law):
    eps = 1e-3
    r = simulate(fmu_path, 0.5, rtol=1e-9, output_interval=1e-3, epsilon=eps, **case, **law)
    E = energy(r, eps, law.get("kappa", 0.0))
    np.testing.assert_allclose(r["energy"], E, rtol=1e-12, atol=1e-12)
    assert r["contact"].any()
    assert np.max(np.diff(E)) < 1e-7 * np.max(np.abs(E))
    assert E[-1] < E[0]


@pytest.mark.parametrize("name, value, words", [
    ("kappa", -1.0, "kappa = -1 is out of range (a softening spring: the compliance law h would increase with y"),
    ("beta", -0.5, "beta = -0.5 is out of range (a damper that reverses: the compliance law h would increase with w"),
])
def test_a_law_that_makes_h_increase_is_refused_naming_it(experiment, name, value, words):
    rod = Rod(experiment)
    with pytest.raises(FMICallException):
        rod.set(**{name: value})
    assert any(words in message for _, _, message in rod.messages), rod.messages
    rod.fmu.freeInstance()
    rod = Rod(experiment)
    rod.set(**{name: 0.0})        # the boundary itself, the linear law, is accepted
    rod.fmu.freeInstance()


VIDEO = dict(theta0=0.9463, phi0=1.6654, v0=1.0, delta=1.0, alpha=3.0, mu=3.0)   # Theorem 2 (b > 0)


def test_theorem2_separatrix_moves_by_order_eps_only(experiment):
    # In Theorem 2's initial layer y = O(eps^2), w = O(eps): h = eps (-Y - delta W) + O(eps^2) with
    # Y = y/eps^2, W = w/eps, so w1* = -lambda_- b/p_+ is h's linear part's; kappa, beta move the
    # bisected boundary by O(eps), not O(1).
    w1s = an.predict(LawCase(**VIDEO)).w1_star
    shifts = {}
    for eps in (1e-2, 1e-3, 1e-4):
        found = {name: separatrix(experiment, LawCase(epsilon=eps, **VIDEO, **law), lower=1.5 * w1s, upper=0.5 * w1s,
                                  tolerance=1e-8)
                 for name, law in [("linear", {}), ("kappa", dict(kappa=20.0)), ("beta", dict(beta=20.0))]}
        for name in ("kappa", "beta"):
            shifts.setdefault(name, []).append(found[name] - found["linear"])
        assert abs(found["kappa"] - w1s) < 2 * eps + abs(found["linear"] - w1s)
    for name, s in shifts.items():
        s = np.array(s)
        assert np.all(np.abs(s) > 0), f"{name}: the law must move the boundary at finite eps: {s}"
        ratio = s[1:] / s[:-1]
        assert np.all((ratio > 0.05) & (ratio < 0.2)), f"{name}: shift {s} must fall like eps"


@pytest.mark.parametrize("law", LAWS)
def test_the_harness_predicts_the_laws_rigid_limit(law):
    # analytic.predict, which iwc, validate's report and sweeps print beside the FMU's outcome,
    # takes e and phi from the rigid limit for a nonlinear law (the linear law's closed form otherwise).
    case = LawCase(theta0=0.9, phi0=0.5, delta=1.0, epsilon=1e-5, **LAWS[law])
    predicted = an.predict(case)
    assert predicted.e == pytest.approx(case.e_law, rel=1e-12) and predicted.phi == pytest.approx(case.phi_law, rel=1e-12)
    assert abs(predicted.e - case.e_linear) > 0.01 * case.e_linear
    assert an.predict(Case(theta0=0.9, phi0=0.5, delta=1.0, epsilon=1e-5)).e == pytest.approx(case.e_linear, rel=1e-12)


def test_painleve_validate_checks_the_theorems_with_a_nonlinear_law(fmu_path):
    # Every theorem case with the law, e from the rigid limit (computed here again), all passing.
    from painleve.validation.suite import validate
    law = dict(kappa=2.0, beta=1.0)
    checks = validate(fmu_path, interfaces=["ME"], sample=2, law=law)
    assert all(c.passed for c in checks), [c.measured for c in checks if not c.passed]
    theorem1 = [c for c in checks if c.id.startswith("theorem1/")]
    assert theorem1 and all("kappa=2 beta=1" in c.what for c in theorem1)
    for c in theorem1:
        case = c.numbers["case"]
        e = rl.e(case["delta"], case["theta0"], v0=case["v0"], alpha=case["alpha"], mu=case["mu"], **law)
        assert c.numbers["e"] == pytest.approx(float(e), rel=1e-10)


def test_the_figure_of_e_against_the_law_puts_the_fmu_on_the_rigid_limit(fmu_path):
    # painleve figures' eLaw: w/v0 of the FMU at eps = 1e-6 on the rigid limit's curve, which leaves
    # the linear e as kappa (up) or beta (down) grows.
    from painleve.figures.paper import elaw_data
    from painleve.fmu.body import Body
    with Body(fmu_path) as body:        # the runner make_figures hands it
        d = elaw_data(body)
    for q in d["points"]:
        law = {q["parameter"]: q["value"]}
        e = float(rl.e(q["delta"], d["params"]["theta0"], alpha=3.0, mu=3.0, **law))
        assert q["e_analytic"] == pytest.approx(e, rel=1e-10) and abs(q["rel_error"]) < 1e-3, q
        linear = float(an.e(q["delta"], d["params"]["theta0"], alpha=3.0, mu=3.0))
        if q["value"] >= 3:
            grows = q["parameter"] == "kappa"
            assert (q["e_simulated"] > 1.05 * linear) if grows else (q["e_simulated"] < 0.95 * linear), q
