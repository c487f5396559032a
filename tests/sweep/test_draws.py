# SPDX-License-Identifier: BSD-2-Clause
"""A random sweep's draws over arrays (sweep.draws: numpy's SeedSequence and PCG64 written over
the batch's ids) are numpy's own default_rng([seed, id]).random(n), bit for bit, for every id and
seed, at the 32-bit words' edges, and outside them (where default_rng itself draws)."""
import numpy as np
import pytest

from painleve.sweep.draws import uniform
from painleve.sweep.spec import PARAMS, SweepSpec


def numpys(seed, ids, n):
    return np.array([np.random.default_rng([seed, int(i)]).random(n) for i in ids]).reshape(-1, n)


@pytest.mark.parametrize("seed", [0, 1, 7, 2**31 + 5, 2**32 - 1, 2**32, 2**40 + 3])
def test_the_draws_over_arrays_are_numpys_bit_for_bit(seed):
    ids = np.concatenate([np.arange(200), [2**16, 2**31 - 1, 2**31, 2**32 - 1, 2**32, 9_999_999]])
    for n in (1, len(PARAMS)):
        want, got = numpys(seed, ids, n), uniform(seed, ids, n)
        assert got.shape == want.shape and np.array_equal(got.view(np.int64), want.view(np.int64))
    assert uniform(seed, np.array([], dtype=np.int64), 3).shape == (0, 3)


def test_a_random_sweeps_cases_are_drawn_as_before():
    spec = SweepSpec.from_texts({"theta0": "0.9:1.2", "epsilon": "1e-5:1e-3:log", "mu": "0.5,1,3"}, samples=500,
                                seed=7)
    ids = np.arange(500)
    u = numpys(7, ids, len(PARAMS))
    cases = spec.cases(ids)
    assert [c.theta0 for c in cases] == list(0.9 + u[:, PARAMS.index("theta0")] * (1.2 - 0.9))
    assert {c.mu for c in cases} == {0.5, 1.0, 3.0}
    assert all(1e-5 <= c.epsilon <= 1e-3 for c in cases)
