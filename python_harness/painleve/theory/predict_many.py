# SPDX-License-Identifier: BSD-2-Clause
"""The paper's predictions for many Cases at once (a sweep's batch): analytic.predict's numbers
with each formula evaluated once over the batch's arrays, not once a case (in numpy on scalars a
case's prediction costs about 200 us, more than its run through the FMU)."""
from operator import attrgetter

import numpy as np

from . import analytic as an

FIELDS = ("theta0", "phi0", "v0", "delta", "epsilon", "w10", "alpha", "mu")
_FIELDS_OF = attrgetter(*FIELDS)


def predict_many(cases):
    """[analytic.predict(case) for case in cases]. The cases of the linear law inside Theorem 1's or
    Theorem 2's hypotheses (check_case's) are checked and computed over arrays, a theorem at a time,
    and handed to predict and check_case; a group with a case outside is checked case by case, and
    the rest (and a group where a formula refuses an element) is left to predict, case by case."""
    groups = {1: [], 2: []}
    for case in cases:   # (iwc_time_scale also needs epsilon < 1, which check_case does not ask)
        if not (case.kappa or case.beta) and 0 < case.epsilon < 1:
            groups[an.theorem_of(case)].append(case)
    seeded = {}
    for theorem, group in groups.items():
        arrays = _arrays(group) if group else None
        if group and not _all_inside(theorem, arrays):
            group = [case for case in group if an.hypothesis_failure(case) is None]
            arrays = _arrays(group) if group else None
        if group:
            try:
                seeded.update(_over_arrays(theorem, group, arrays))
            except (ValueError, ArithmeticError):     # as predict's _or_nan: that group case by case
                pass
    an.seed_predictions(seeded)
    return [an.predict(case) for case in cases]


def _arrays(group):
    """The group's FIELDS, each a contiguous float array."""
    table = np.array([_FIELDS_OF(c) for c in group], dtype=float).reshape(len(group), len(FIELDS))
    return tuple(np.ascontiguousarray(table[:, k]) for k in range(len(FIELDS)))


def _all_inside(theorem, arrays):
    """Whether every case of a group (all of one theorem; its _arrays) is inside its hypotheses, as
    check_case asks them, checked over arrays."""
    th, ph, v0, delta, _, w10, alpha, mu = arrays
    check = an.check_theorem1 if theorem == 1 else an.check_theorem2
    try:
        check(th, ph, v0, alpha=alpha, mu=mu, delta=delta)
    except an.HypothesisError:
        return False
    return theorem == 1 or bool(np.all(w10 < 0))


def _over_arrays(theorem, group, arrays):
    """{case: Prediction} of cases of one theorem (their _arrays), each formula once over their arrays."""
    th, ph, v0, delta, eps, w10, alpha, mu = arrays
    rod = dict(alpha=alpha, mu=mu)
    e = np.atleast_1d(an.e(delta, th, **rod))
    phi = np.atleast_1d(an.phi_after_iwc(th, ph, v0, delta, e=e, **rod))
    lp = np.atleast_1d(an.lambda_pm(th, delta, **rod)[0])
    ts = np.atleast_1d(an.iwc_time_scale(eps, th, delta, **rod))
    w1s = np.atleast_1d(an.w1_star(th, ph, delta, **rod)) if theorem == 2 else np.full(len(group), np.nan)
    return {case: an.Prediction(theorem=theorem, e=float(e[i]), phi=float(phi[i]), lambda_plus=float(lp[i]),
                                time_scale=float(ts[i]), w1_star=float(w1s[i]),
                                iwc=None if theorem == 2 and np.isnan(w1s[i]) else theorem == 1 or w10[i] < w1s[i])
            for i, case in enumerate(group)}
