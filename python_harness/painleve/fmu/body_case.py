# SPDX-License-Identifier: BSD-2-Clause
"""One IWC case of any body FMU: the start it solves for, what the theory predicts from the FMU's
coefficient outputs there (theory.general), and what the FMU does (fmu.body)."""
import math
from dataclasses import dataclass

from ..theory import general
from ..theory.hypotheses import HypothesisError
from .body import Body


@dataclass(frozen=True)
class BodyCase:
    """A start on the floor: the start values the user gives (parameters, some states), the contact
    point's slip speed v0 (None: that of the FMU's own start) and normal speed w0 (the FMU's units),
    the compliance eps, delta."""
    given: tuple          # ((name, value), ...)
    v0: float = None
    epsilon: float = 1e-3
    delta: float = 1.0
    w0: float = 0.0
    guess: tuple = ()


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


def predict(body: Body, case: BodyCase) -> BodyPrediction:
    values = body.compliance(dict(case.given), case.epsilon, case.delta)
    v0 = body.outputs(values, ("v",))["v"] if case.v0 is None else case.v0
    start = body.floor_start(values, v0, case.w0, guess=dict(case.guess))
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


def run_body(body: Body, case: BodyCase):
    """(BodyPrediction, Outcome) of one case, through the interface `body` was opened with."""
    predicted = predict(body, case)
    return predicted, body.iwc(predicted.start, case=case)

