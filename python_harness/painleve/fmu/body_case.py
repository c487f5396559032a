# SPDX-License-Identifier: BSD-2-Clause
"""One IWC case of any body FMU, of either kind (experiments.case: a BodyCase, or the rod's Case): the
start it solves for, what the theory predicts from the FMU's coefficient outputs there (theory.general),
and what the FMU does (fmu.body)."""
import math
from dataclasses import dataclass

from ..experiments.case import BodyCase, Case, IWCCase
from ..theory import general
from ..theory.hypotheses import HypothesisError
from .body import Body

__all__ = ["BodyCase", "BodyPrediction", "Case", "IWCCase", "predict", "run_body"]


@dataclass(frozen=True)
class BodyPrediction:
    start: dict           # every start value the run uses (the solved states included)
    start_v0: float       # the slip speed it starts with
    coefficients: object  # theory.general.Coefficients at the start
    epsilon: float
    delta: float
    quadrant: str
    theorem: int          # 1 (b < 0) or 2 (b > 0)
    e: float              # eq eGeneral; NaN outside its hypotheses
    w1_star: float        # Theorem 2's separatrix (scaled w/eps); NaN for Theorem 1
    hypotheses: str       # "" if Theorem 1 or 2 covers the start, else what fails


def predict(body: Body, case: IWCCase) -> BodyPrediction:
    """The start of `case` on the floor and the theory there, from the FMU's own coefficient outputs."""
    values = body.compliance(dict(case.given), case.epsilon, case.delta)
    v0 = body.outputs(values, ("v",))["v"] if case.v0 is None else case.v0
    start = body.floor_start(values, v0, case.w0, guess=dict(case.guess), solve=tuple(case.solve))
    co, eps, delta = body.coefficients(start)
    theorem = int(general.theorem_of(co))
    failed = ""
    try:
        general.check(co, theorem, delta=delta, v0=v0)
    except HypothesisError as err:
        failed = str(err)
    if theorem == 2 and not failed and not case.w0 < 0:
        failed = f"Theorem 2 (b > 0) starts moving down, w0 = eps w10 with w10 < w1* < 0; got w0 = {case.w0:g}"
    e = w1s = math.nan
    try:
        e = float(general.e(delta, co))
        if theorem == 2:
            w1s = float(general.w1_star(delta, co))
    except HypothesisError:
        pass
    return BodyPrediction(start=start, start_v0=v0, coefficients=co, epsilon=eps, delta=delta, quadrant=str(general.quadrant(co)),
                          theorem=theorem, e=e, w1_star=w1s, hypotheses=failed)


def run_body(body: Body, case: IWCCase, **run):
    """(BodyPrediction, Outcome) of one case of either kind, through the interface `body` was opened with
    (Body.run, with `run`'s keywords), the prediction attached to the Outcome (its w_error, as_row)."""
    predicted = predict(body, case)
    return predicted, body.run(case, predicted, **run)

