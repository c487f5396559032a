# SPDX-License-Identifier: BSD-2-Clause
"""One Outcome for every case: its w error and its row serve the rod's Case (its closed forms) and a
body's case (the e of theory.general at its start, from the FMU's coefficients, which run_body attaches)
alike. On the rod both must be Theorem 1's e(delta, theta0), computed here by the exact integration of
the sticking system (analytic.e_integrated), and w/v0 must meet it to O(eps ln 1/eps)."""
import pytest

from conftest import built_fmu
from helpers.rod_sim import theorem_bound
from painleve.experiments.case import BodyCase, Case
from painleve.fmu.body import Body
from painleve.fmu.body_case import run_body
from painleve.theory.analytic import e_integrated

THETA0, PHI0, DELTA, V0, EPS = 1.0, 0.5, 0.5, 1.3, 1e-5     # inside the wide wedge of alpha = mu = 3: Theorem 1
BODY_CASE = BodyCase(given=(("theta", THETA0), ("phi", PHI0), ("x", 0.0)), v0=V0, epsilon=EPS, delta=DELTA)
ROD_CASE = Case(theta0=THETA0, phi0=PHI0, v0=V0, delta=DELTA, epsilon=EPS)


@pytest.fixture(scope="module", params=["ModelExchange", "CoSimulation"])
def outcomes(request):
    """(the rod's Case's Outcome, the same start's BodyCase's Outcome), both through run_body."""
    with Body(built_fmu("PainleveRod.fmu"), fmi_type=request.param) as body:
        return run_body(body, ROD_CASE)[1], run_body(body, BODY_CASE)[1]


def test_a_body_cases_w_error_is_w_over_v0_minus_the_e_at_its_start(outcomes):
    _, body = outcomes
    e = e_integrated(DELTA, THETA0)
    assert body.prediction is not None and body.prediction.start_v0 == V0
    assert body.w_error == pytest.approx(body.w / V0 - e, abs=1e-9)
    assert abs(body.w_error) < theorem_bound(BODY_CASE)


def test_the_rods_case_keeps_its_closed_form_beside_the_general_prediction(outcomes):
    rod, body = outcomes
    e = e_integrated(DELTA, THETA0)
    assert rod.prediction is not None      # run_body attached theory.general's; the rod's e is its closed form
    assert rod.w_error == pytest.approx(rod.w / V0 - e, abs=1e-9)
    assert abs(rod.w_error) < theorem_bound(ROD_CASE)
    # the same start run as either kind of case: one physics, to the solver's tolerance
    assert rod.w == pytest.approx(body.w, rel=1e-4) and rod.iwc and body.iwc


def test_a_body_cases_row_holds_its_start_the_theory_there_and_the_run(outcomes):
    _, body = outcomes
    row = body.as_row()
    e = e_integrated(DELTA, THETA0)
    assert (row["theta"], row["phi"], row["x"]) == (THETA0, PHI0, 0.0)      # the start values given
    assert (row["v0"], row["epsilon"], row["delta"], row["w0"]) == (V0, EPS, DELTA, 0.0)
    assert row["e"] == pytest.approx(e, rel=1e-9) and row["predicted_w"] == pytest.approx(e * V0, rel=1e-9)
    assert row["theorem"] == 1 and row["p_plus"] < 0 and row["b"] < 0     # Theorem 1: the paradox, b < 0
    assert row["iwc"] and row["w_error"] == body.w_error and row["w"] == body.w
    # the phases of an IWC that starts on the floor add up to its return time
    assert row["compression"] + row["stick"] + row["lift_off"] + row["flight_back"] == pytest.approx(row["t_return"])


def test_a_body_cases_w_error_without_its_prediction_says_how_to_get_one():
    with Body(built_fmu("PainleveRod.fmu")) as body:
        start = dict(BODY_CASE.given, y=0.0, v=V0, w=0.0, epsilon=EPS, delta=DELTA)
        outcome = body.iwc(start, case=BODY_CASE)
    assert outcome.prediction is None
    with pytest.raises(ValueError, match="run_body"):
        outcome.w_error
