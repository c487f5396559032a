# SPDX-License-Identifier: BSD-2-Clause
"""`painleve validate` has one way through for every body FMU (validation.body.validate_fmu): the rod's
own suite and a body's case alike run every case through fmu.body.Body.run, through either interface;
and what they report is the physics: the rod's cases converge to Theorem 1's e(delta, theta0), computed
here by the exact integration of the sticking system (analytic.e_integrated)."""
from dataclasses import replace

import pytest

from painleve.experiments.case import BodyCase, Case
from painleve.validation.body import validate_fmu


@pytest.mark.parametrize("interface", ["ME", "CS"])
def test_the_rods_suite_runs_every_case_through_the_body_runner(fmu_path, ran, interface):
    checks = validate_fmu(fmu_path, interfaces=[interface], sample=0)
    assert checks and all(c.passed for c in checks)
    fmi_type = {"ME": "ModelExchange", "CS": "CoSimulation"}[interface]
    assert ran and {t for t, _ in ran} == {fmi_type} and all(isinstance(c, Case) for _, c in ran)
    theorem1 = [c for c in checks if c.id.startswith(f"theorem1/{interface}/")]
    assert len(theorem1) >= 15
    for check in theorem1:
        n = check.numbers
        case = Case(**n["case"])
        # each eps of the check was a run of the body runner
        assert all(replace(case, epsilon=eps) in [c for _, c in ran] for eps in n["epsilons"])
        assert n["e"] == pytest.approx(_e(case), rel=1e-7)
        assert n["iwc"] and abs(n["w_rel_errors"][-1]) <= 0.01     # Theorem 1: w/v0 -> e as eps -> 0


def test_a_body_case_on_the_rod_takes_the_same_runner_to_the_same_e(fmu_path, ran):
    case = BodyCase(given=(("theta", 1.0), ("phi", 0.5), ("x", 0.0)), v0=1.0, delta=0.5)
    checks = validate_fmu(fmu_path, case, interfaces=["ME"])
    assert all(c.passed for c in checks)
    assert [c.epsilon for _, c in ran] == [1e-4, 1e-5, 1e-6] and all(isinstance(c, BodyCase) for _, c in ran)
    e = _e(Case(theta0=1.0, phi0=0.5, delta=0.5))
    for check in checks:
        if check.id.endswith("/iwc"):
            assert check.numbers["e"] == pytest.approx(e, rel=1e-7)
            assert check.numbers["w_over_v0"] == pytest.approx(e, rel=0.01)


def _e(case):
    from painleve.theory.analytic import e_integrated
    return e_integrated(case.delta, case.theta0, alpha=case.alpha, mu=case.mu)


def test_the_commands_validate_and_sweep_of_the_rod_take_the_body_runner(fmu_path, ran, tmp_path, capsys):
    """`painleve validate FMU` and `painleve sweep --fmu FMU` (the rod's own cases, no --set) as a user
    types them, run in this process: their cases are Body.run's, and the sweep's rows Theorem 1's e."""
    import json

    import pandas as pd

    from painleve.cli.main import main
    from painleve.sweep.run import _close_bodies
    assert main(["validate", fmu_path, "--interface", "ME", "--sample", "0", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["passed"] and ran and all(isinstance(c, Case) for _, c in ran)
    ran.clear()
    out = tmp_path / "sweep.csv"
    try:
        assert main(["sweep", "--fmu", fmu_path, "--theta0", "0.6:1.2:4", "--eps", "1e-5", "--serial",
                     "--no-progress", "--interface", "CS", "--out", str(out)]) == 0
    finally:
        _close_bodies()
    df = pd.read_csv(out)
    assert [c.theta0 for _, c in ran] == list(df["theta0"]) and {t for t, _ in ran} == {"CoSimulation"}
    for row in df.itertuples():
        assert row.status == "ok" and row.e == pytest.approx(_e(Case(theta0=row.theta0, delta=row.delta)), rel=1e-7)
