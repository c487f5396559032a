# SPDX-License-Identifier: BSD-2-Clause
"""predict_many (a sweep batch's predictions over arrays) gives analytic.predict's numbers case by
case: Theorem 1 and 2 cases, cases outside the hypotheses (NaN where predict has NaN), a nonlinear
law (case by case), in one mixed batch."""
import math
from dataclasses import fields

import numpy as np
import pytest

from painleve.experiments.case import Case
from painleve.theory import analytic as an
from painleve.theory.predict_many import predict_many


def mixed_cases():
    rng = np.random.default_rng(3)
    cases = [Case(theta0=float(rng.uniform(0.5, 1.5)), phi0=float(rng.uniform(0, 2)),
                  delta=float(rng.uniform(0, 2)), epsilon=float(10 ** rng.uniform(-6, -1)),
                  w10=float(rng.uniform(-3, 1)), v0=float(rng.uniform(0.2, 2)))
             for _ in range(300)]
    return cases + [Case(kappa=2.0), Case(mu=0.1), Case(epsilon=1.0), Case(theta0=0.9463, phi0=1.6654, w10=0.5)]


def test_predict_many_is_predict_case_by_case(monkeypatch):
    cases = mixed_cases()
    seeded = []
    seed = an.seed_predictions
    monkeypatch.setattr(an, "seed_predictions", lambda p: (seeded.extend(p), seed(p)))
    an.predict.cache_clear()
    many = predict_many(cases)
    an.predict.cache_clear()
    inside = {1: 0, 2: 0}
    for case, got in zip(cases, many):
        want = an.predict(case)
        if an.hypothesis_failure(case) is None and case.epsilon < 1 and not case.kappa:
            inside[want.theorem] += 1
        for f in fields(want):
            a, b = getattr(got, f.name), getattr(want, f.name)
            if isinstance(b, float) and not math.isnan(b):
                assert math.isclose(a, b, rel_tol=1e-14, abs_tol=1e-300), (case, f.name)
            elif isinstance(b, float):
                assert math.isnan(a), (case, f.name)
            else:
                assert a == b, (case, f.name)
    assert inside[1] > 50 and inside[2] > 50
    assert len(seeded) == inside[1] + inside[2]      # every case inside went through the arrays
    assert not an._SEEDED                            # and predict took each


def test_a_batch_inside_the_hypotheses_is_checked_over_arrays(monkeypatch):
    rng = np.random.default_rng(4)
    t1 = [Case(theta0=float(rng.uniform(0.9, 1.2)), delta=float(rng.uniform(0, 2)),
               epsilon=float(10 ** rng.uniform(-5, -3))) for _ in range(100)]
    t2 = [Case(theta0=0.9463, phi0=1.6654, w10=float(rng.uniform(-3, -0.1)), epsilon=1e-4) for _ in range(50)]
    an.predict.cache_clear()
    an.hypothesis_failure.cache_clear()
    many = predict_many(t1 + t2)
    for case in t1 + t2:
        case.check()                                  # passes: inside, as the arrays found
    assert an.hypothesis_failure.cache_info().currsize == 0    # without checking a case alone
    assert [p.theorem for p in many] == [1] * 100 + [2] * 50
    an.predict.cache_clear()
    for case, got in zip(t1 + t2, many):
        want = an.predict(case)
        assert math.isclose(got.e, want.e, rel_tol=1e-14) and math.isclose(got.phi, want.phi, rel_tol=1e-14)
        assert got.iwc == want.iwc and math.isclose(got.time_scale, want.time_scale, rel_tol=1e-14)
    outside = Case(mu=0.1)
    predict_many([outside] + t1)
    with pytest.raises(an.HypothesisError):
        outside.check()
