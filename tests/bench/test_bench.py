# SPDX-License-Identifier: BSD-2-Clause
"""The benchmark's runners compute the same IWC, and its growth fit reads exponents right.
(Speed is the benchmark's business, bench/bench.py; here only what its numbers mean.)"""
import math
import sys

import pytest

from painleve.theory import analytic as an
from conftest import ROOT

sys.path.insert(0, str(ROOT / "bench"))
import bench  # noqa: E402


@pytest.fixture(scope="module")
def runners(fmu_path):
    if not bench.NATIVE.exists():
        pytest.fail(f"{bench.NATIVE} is missing: `bash run.sh test` builds it")
    r = bench.Runners()
    yield r
    r.close()


@pytest.mark.parametrize("eps", [1e-3, 1e-5])
def test_every_runner_gives_the_same_iwc(runners, eps):
    cases = bench.cases_at(eps)
    blocks = {name: runners.run_block(name, cases) for name in runners.names()}
    for i, case in enumerate(cases):
        ws = {name: block[i][1]["w"] for name, block in blocks.items()}
        rtol = min(1e-6, eps / 100)
        for name, w in ws.items():
            if name == "fmpy ME Euler":     # first order, h = eps/100: a few % of w (test_second_importer)
                assert w == pytest.approx(ws["native"], rel=0.05), name
            else:                           # every CVODE and scipy run at rtol: agree to ~100 rtol
                assert abs(w - ws["native"]) <= 100 * rtol * case.v0, (name, w, ws["native"])
        if an.predict(case).iwc:               # Theorem 1/2: w/v0 -> e, error O(eps ln 1/eps)
            assert abs(ws["native"] / case.v0 - an.predict(case).e) < 3 * eps * math.log(1 / eps)
        else:                               # above w1*: lifts off with w = O(eps)
            assert 0 < ws["native"] < 5 * eps


def test_growth_fit_reads_the_exponent_of_ln_one_over_eps():
    epsilons = bench.EPSILONS
    for p in (0.0, 0.5, 1.0, 2.0):
        counts = {e: 40 * math.log(1 / e) ** p for e in epsilons}
        assert bench.growth(counts) == pytest.approx(p, abs=1e-9)
    assert math.isnan(bench.growth({e: None for e in epsilons}))


def test_equal_accuracy_takes_the_loosest_tolerance_that_meets_the_target(runners):
    eps = 1e-3
    ref = bench.tightest([eps])
    target = bench.accuracy_targets(ref, [eps])[eps]
    # 1 % of the model's own error, which is O(eps ln 1/eps) (Theorem 1)
    assert 0 < target < 0.03 * eps * math.log(1 / eps)
    names = ["fmpy ME fast loop", "scipy DOP853"]
    chosen = bench.equal_accuracy_rtols(runners, ref, {eps: target}, names=names)
    for name in names:
        rtol, err = chosen[name, eps]
        assert err <= target, name
        looser = bench.LADDER.index(rtol) - 1
        if looser >= 0:
            assert bench.max_error(runners, name, eps, bench.LADDER[looser], ref) > target, name


def test_si_rod_one_step_gives_the_scaled_rods_lift_off(si_fmu_path):
    """The SI table's runs (bench/si_table.py): PainleveRodSI through one fmi2DoStep, in the paper's
    units, lifts off with the w of scipy's DOP853 on the scaled model (an independent code) to 1e-6."""
    import si_table
    from painleve.experiments import reference
    from painleve.fmu.experiment import Experiment
    with Experiment(si_fmu_path, fmi_type="CoSimulation") as ex:
        for case in bench.cases_at(1e-4):
            w_ref = reference.run_reference(case, method="DOP853", relative_tolerance=1e-12).w
            _, state, switches = si_table.run_once(ex, case, 1e-6)
            assert abs(si_table.w_at_return(state) - w_ref) <= 1e-6, case
            assert switches >= 1
