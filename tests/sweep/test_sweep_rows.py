# SPDX-License-Identifier: BSD-2-Clause
"""A sweep's row of a case is the generic harness's, bit for bit: the sweep's path (the FMI calls
straight into the FMU's C functions, the batch's predictions over arrays handed to each run, the
row a tuple) against a second, generic one (Experiment.run through fmpy's wrappers, Outcome.as_row
and predict's columns, a dict a row), for random cases that run, fall outside the theorems'
hypotheses, or fail; and the rows carry the physics: w at the return on Theorem 1's e."""
from dataclasses import asdict

import numpy as np
import pandas as pd
import pytest

from painleve.experiments.outcome import SimulationError
from painleve.fmu.experiment import Experiment
from painleve.sweep.run import FmuBlob, _close_bodies, predictions, run_batch
from painleve.sweep.spec import SweepSpec
from painleve.sweep.store import as_frame
from painleve.theory import analytic as an
from painleve.theory.predict_many import predict_many

SPEC = SweepSpec.from_texts({"theta0": "0.3:1.5", "phi0": "0:2", "w10": "-2:1", "epsilon": "1e-5:1e-2:log",
                             "delta": "0:2"}, samples=400, seed=11)


def generic_rows(fmu_path, ids):
    """The rows as the harness's generic path makes them, case by case."""
    cases = SPEC.cases(ids)
    predict_many(cases)     # the batch's predictions, which predict then returns: the sweep's numbers
    rows = []
    with Experiment(fmu_path, fmi_type="CoSimulation", direct_calls=False) as experiment:
        for i, case in zip(ids, cases):
            row = {"id": int(i), **predictions(case)}
            try:
                case.check()
                row.update(experiment.run(case).as_row(), status="ok", message="")
            except an.HypothesisError as err:
                row.update(asdict(case), status="outside", message=str(err))
            except SimulationError as err:
                row.update(asdict(case), status="failed", message=str(err))
            rows.append(row)
    return as_frame(rows)


def test_a_sweeps_rows_are_the_generic_harness_path_bit_for_bit(fmu_path):
    ids = np.arange(SPEC.total)
    try:
        swept = pd.concat([run_batch(SPEC, chunk, FmuBlob.read(fmu_path), "CoSimulation")
                           for chunk in np.array_split(ids, 3)], ignore_index=True)
    finally:
        _close_bodies()        # this process's instance (a sweep's goes at exit)
    generic = generic_rows(fmu_path, ids)
    assert set(swept["status"]) == {"ok", "outside", "failed"}
    pd.testing.assert_frame_equal(swept, generic, check_exact=True)
    for name, column in swept.items():       # floats as their bits: -0.0 is not 0.0
        if column.dtype == "float64":
            assert np.array_equal(column.to_numpy().view(np.int64), generic[name].to_numpy().view(np.int64)), name
    fine = swept[(swept["status"] == "ok") & (swept["theorem"] == 1) & (swept["epsilon"] < 1e-4)]
    # Theorem 1: w/v0 - e = O(eps ln 1/eps), below 1.2e-3 here
    assert len(fine) >= 10 and np.all(np.abs(fine["w_error"]) < 2e-3)


def test_a_sweeps_cases_run_through_the_body_runner_and_land_on_theorem_1(fmu_path, ran):
    """The rod's sweep has no runner of its own: every case that runs is fmu.body.Body.run's (the runner
    of every body FMU), through either interface; and its rows carry the physics: e is Theorem 1's,
    by the exact integration of the sticking system, and w/v0 meets it to O(eps ln 1/eps)."""
    spec = SweepSpec.from_texts({"theta0": "0.3:1.2:6", "delta": "0,1", "epsilon": "1e-5"})
    for fmi_type in ("ModelExchange", "CoSimulation"):
        ran.clear()
        try:
            df = run_batch(spec, np.arange(spec.total), FmuBlob.read(fmu_path), fmi_type)
        finally:
            _close_bodies()
        cases = spec.cases(np.arange(spec.total))
        inside = [c for c, status in zip(cases, df["status"]) if status != "outside"]
        assert ran == [(fmi_type, c) for c in inside] and 0 < len(inside) < spec.total   # theta0 = 0.3: outside
        ok = df[df["status"] == "ok"]
        assert len(ok) == len(inside)
        for row in ok.itertuples():
            assert row.e == pytest.approx(an.e_integrated(row.delta, row.theta0), rel=1e-7)
            assert abs(row.w / row.v0 - row.e) < 2e-3      # O(eps ln 1/eps) at eps = 1e-5, as above
            assert row.w_error == row.w / row.v0 - row.e
