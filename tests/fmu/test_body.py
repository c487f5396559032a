# SPDX-License-Identifier: BSD-2-Clause
"""The generic body path (painleve.fmu.body) on the rod FMUs: coefficients read from the FMU's
outputs, the start state solved from its own y, v, w, the IWC run; it must give the rod's known e
(analytic's closed form, an independent path: the rod's own formulas at theta0), the error falling
with eps as Theorem 1 says. The SI rod goes through the other way of setting eps and delta (k, c)."""
import numpy as np
import pytest

from conftest import built_fmu
from painleve import Body, BodyCase, Case, Experiment, IWCCase, Outcome, run_body
from painleve.fmu.body import BodyError
from painleve.theory import analytic as A
from painleve.theory import general as G


@pytest.fixture(scope="module")
def rod():
    with Body(built_fmu("PainleveRod.fmu")) as body:
        yield body


def test_the_rods_coefficient_outputs_are_its_formulas(rod):
    co, eps, delta = rod.coefficients(dict(theta=1.1, phi=0.4, epsilon=1e-3, delta=0.7))
    assert (eps, delta) == (1e-3, 0.7)
    for name, f in (("p_plus", A.p_plus), ("p_minus", A.p_minus), ("q_plus", A.q_plus), ("q_minus", A.q_minus)):
        assert getattr(co, name) == pytest.approx(f(1.1), rel=1e-13)
    assert co.S_w == pytest.approx(A.S_w(1.1), rel=1e-13)
    assert (co.a, co.b) == (pytest.approx(A.a(1.1, 0.4), rel=1e-13), pytest.approx(A.b(1.1, 0.4), rel=1e-13))


def test_the_floor_start_is_solved_from_the_fmus_own_outputs(rod):
    start = rod.floor_start(dict(theta=1.0, phi=0.5, x=0.0), 1.3, w0=-2e-4)
    out = rod.outputs(start, ("y", "v", "w"))
    assert out == pytest.approx(dict(y=0.0, v=1.3, w=-2e-4), abs=1e-15)
    given = dict(x=0, v=1, y=0, w=0, theta=1, phi=0.5)
    assert rod.floor_start(given, 1.0) == given                # every state given, on the floor: itself
    with pytest.raises(BodyError, match="not on the floor"):
        rod.floor_start(dict(given, y=1e-3), 1.0)


@pytest.mark.parametrize("fmi_type", ["ModelExchange", "CoSimulation"])
@pytest.mark.parametrize("fmu,given,v0", [("PainleveRod.fmu", dict(theta=1.0, phi=0.5, x=0.0), 1.0),
                                          ("PainleveRodSI.fmu", dict(theta=0.9, phi=1.5, x=0.0), 2.0)])
def test_the_generic_iwc_gives_the_rods_e(fmu, given, v0, fmi_type):
    delta, theta0 = 1.0, given["theta"]
    e = A.e(delta, theta0, alpha=3.0, mu=3.0)
    errors = []
    with Body(built_fmu(fmu), fmi_type=fmi_type) as body:
        for eps in (1e-3, 1e-4, 1e-5):
            start = body.floor_start(body.compliance(given, eps, delta), v0)
            co, got_eps, got_delta = body.coefficients(start)
            assert got_eps == pytest.approx(eps, rel=1e-9) and got_delta == pytest.approx(delta, rel=1e-9)
            assert G.e(got_delta, co) == pytest.approx(e, rel=1e-9)
            out = body.iwc(start)
            assert out.iwc and out.y >= 0 and abs(out.v) < 0.05 * v0
            errors.append(abs(out.w / v0 - e))
    assert errors[-1] < 2e-3 * e
    assert errors[-1] < errors[0] / 10                         # two decades of eps: > 10 times smaller


def test_a_fmu_without_the_body_variables_is_refused():
    with pytest.raises(BodyError, match="not a body FMU"):
        Body(built_fmu("ShakerTable.fmu"))


def test_no_start_state_is_named(rod):
    with pytest.raises(BodyError, match="no state with y = 0"):
        rod.floor_start(dict(theta=1.0, phi=0.5, x=0.0, y=0.3), 1.0)   # y given off the floor
    assert np.isfinite(rod.outputs(dict(theta=1.0), ("p_plus",))["p_plus"])


def test_the_rod_through_the_generic_path_is_the_rods_own_run(rod):
    """One Outcome for both paths: the rod's own Case through Experiment.run and the same start through
    Body.iwc are the same run (the same runner, the same return rule): the same state at the return."""
    case = Case(theta0=1.0, phi0=0.5, v0=1.0, delta=1.0, epsilon=1e-4)
    with Experiment(built_fmu("PainleveRod.fmu")) as ex:
        own = ex.run(case)
    start = {k: v for k, v in case.start_values().items() if k not in ("kappa", "beta")}
    generic = rod.iwc(start, relative_tolerance=min(1e-6, case.epsilon / 100), horizon=0.01)
    assert isinstance(own, Outcome) and isinstance(generic, Outcome)
    assert (generic.iwc, generic.events) == (own.iwc, own.events)
    for k in ("w", "v", "theta", "phi"):
        assert getattr(generic, k) == pytest.approx(getattr(own, k), rel=1e-6, abs=1e-9)
    assert generic.w == pytest.approx(A.e(1.0, 1.0), rel=2e-3)


def test_the_public_face_runs_any_body_through_co_simulation():
    with Body(built_fmu("TwoLinkArm.fmu"), fmi_type="CoSimulation") as body:
        predicted, outcome = run_body(body, BodyCase(given=(), epsilon=1e-5))
    assert isinstance(outcome, Outcome) and outcome.iwc and outcome.events >= 2
    assert outcome.w / predicted.start_v0 == pytest.approx(predicted.e, rel=3e-3)   # Theorem 1 at eps = 1e-5


@pytest.mark.parametrize("fmi_type", ["ModelExchange", "CoSimulation"])
def test_the_rods_case_is_a_case_of_the_general_path_and_gives_the_analytic_e(fmi_type):
    """The rod's Case is one kind of case: run_body takes it as it takes a BodyCase. Its prediction comes
    from the FMU's coefficient outputs through theory.general, and must be the rod's closed form e (eq
    eGeneral on eq coeffs at theta0, an independent path); its run is the rod's own (Experiment.run), the
    same numbers; and the simulated w/v0 is e to Theorem 1's O(eps ln 1/eps)."""
    case = Case(theta0=1.0, phi0=0.5, v0=1.3, delta=0.5, epsilon=1e-5)
    assert isinstance(case, IWCCase) and isinstance(BodyCase(given=()), IWCCase)
    assert dict(case.given)["w"] == case.w0 == 0 and case.solve == case.guess == ()
    assert case.configuration()["theta0"] == 1.0 and BodyCase(given=(("x", 0.0),)).configuration()["given"] == (("x", 0.0),)
    with Body(built_fmu("PainleveRod.fmu"), fmi_type=fmi_type) as body:
        predicted, outcome = run_body(body, case)
    with Experiment(built_fmu("PainleveRod.fmu"), fmi_type=fmi_type) as ex:
        own = ex.run(case)
    e = A.e(0.5, 1.0)
    assert predicted.e == pytest.approx(e, rel=1e-12) and predicted.theorem == 1 and not predicted.hypotheses
    assert predicted.start == case.start_values() and predicted.start_v0 == 1.3
    assert outcome == own and outcome.state == own.state
    assert outcome.w / case.v0 == pytest.approx(e, rel=1e-3) and outcome.w_error == pytest.approx(0, abs=1e-3)
