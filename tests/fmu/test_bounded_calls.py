# SPDX-License-Identifier: BSD-2-Clause
"""Every call returns: random legal cases of every built FMU, both
interfaces and FMI versions (bench/bounded_cases.py draws them: parameters within
the model description's min/max, states, inputs, tolerances from 1e-14 to 48.125,
start times, step sizes; Model Exchange through fmpy's CVode and Euler, Co-Simulation
step by step), each in a worker process under a wall limit, and the calls that once hung.

A case fails on a hang (past the wall limit), a crash, an error whose log says
"Zeno" (a give-up where the motion goes on), a Discard from anything but a doStep,
or getters that fail (or give NaN) after a doStep's Discard (FMI 2.0.4 §4.2.2 and
FMI 3.0 §4.2.1: the master may still read the outputs). An Error with a reason
(a state out of its range after Euler blew up, an illegal tolerance refused) and
a doStep's Discard (a budget ran out) are answers, not failures.

BOUNDED_CASES (default 360), BOUNDED_SEED (1) and BOUNDED_WALL (seconds, 10) set
the run; a failing case is replayed alone by
`python bench/bounded_calls.py --seed SEED --only INDEX`."""
import os
import sys

import pytest

from conftest import ROOT, built_fmu

sys.path.insert(0, str(ROOT / "bench"))
import bounded_cases as bc  # noqa: E402
import bounded_runs as br  # noqa: E402

CASES = int(os.environ.get("BOUNDED_CASES", "360"))
SEED = int(os.environ.get("BOUNDED_SEED", "1"))
WALL = float(os.environ.get("BOUNDED_WALL", "10"))


def test_every_call_returns_on_random_legal_cases():
    for path in bc.FMUS.values():
        built_fmu(path.removeprefix("build/"))
    models = bc.read_models()
    cases = bc.regression_cases(models) + [bc.make_case(models, SEED, k) for k in range(CASES)]
    results = br.run_cases(models, cases, WALL)
    assert sorted(results) == sorted(case["index"] for case in cases)
    failed = [(case, results[case["index"]]) for case in cases if results[case["index"]]["outcome"] in br.FAILURES]
    if failed:
        pytest.fail(f"{len(failed)} of {len(cases)} cases failed:\n" + "\n".join(
            f"{result['outcome'].upper()}: {bc.describe(case)}\n    {result['detail'][:400]}"
            for case, result in failed), pytrace=False)
    # every combination of model, FMI version, interface and solver ran
    ran = {(c["model"], c["fmi"], c["interface"], c.get("solver")) for c in cases if c["index"] >= 0}
    assert ran == set(bc.COMBOS)
