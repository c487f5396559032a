# SPDX-License-Identifier: BSD-2-Clause
"""`painleve sweep` on a body FMU (sweep.body): the arm's grid over theta1 and mu, and its random draws
over (theta1, theta2, mu, eps) with the pivot height H solved to put the tip on the floor; each row's
theory checked against the independent numpy arm (helpers.arm_lagrange), its simulation against the
sign of p_plus and Theorem 1; a rod option the body's sweep cannot honour is refused."""
import numpy as np
import pandas as pd
import pytest

from conftest import built_fmu
from helpers.arm_lagrange import Arm, coefficients, tip
from helpers.cli_run import one_line_error, run
from painleve.fmu.body import Body

GRID = ["--set", "theta1=-1.25,-1.2,-1.0", "--set", "mu=0.5,1,2", "--guess", "theta2=-1.3", "--v0", "0.2",
        "--eps", "1e-5"]


def fmu_arm(mu):
    """The numpy arm with TwoLinkArm.fmu's own default parameters (read from the FMU) and this mu."""
    with Body(built_fmu("TwoLinkArm.fmu")) as body:
        p = body.defaults(("H", "m1", "l1", "J1", "m2", "l2", "J2", "g"))
    return Arm(**p, mu=mu)


@pytest.mark.parametrize("interface", ["ME", "CS"])
def test_the_arms_sweep_maps_the_paradox_by_simulation_beside_the_theory(tmp_path, interface):
    out = tmp_path / "arm.csv"
    r = run("sweep", "--fmu", built_fmu("TwoLinkArm.fmu"), *GRID, "--interface", interface, "--out", out, check_rc=0)
    assert "9 cases" in r.stdout and "paradox map" in r.stdout
    df = pd.read_csv(out)
    assert list(df["id"]) == list(range(9)) and list(df["theta1"]) == [-1.25] * 3 + [-1.2] * 3 + [-1.0] * 3
    started = df[df["status"] != "failed"]
    assert len(started) == 9
    for row in started.itertuples():
        numpy = coefficients(fmu_arm(row.mu), np.array([row.theta1, row.start_theta2]),
                             np.array([row.start_omega1, row.start_omega2]))
        assert row.p_plus == pytest.approx(numpy["p_plus"], rel=1e-9)
        assert row.b == pytest.approx(numpy["b"], rel=1e-9, abs=1e-12)
    ok = df[df["status"] == "ok"]
    assert len(ok) >= 4 and (ok["p_plus"] < 0).all() and ok["iwc"].astype(bool).all()
    assert (ok["w"] / ok["v0"]).to_numpy() == pytest.approx(ok["e"].to_numpy(), rel=5e-3)   # Theorem 1, eps 1e-5
    # outside the paradox (p_plus > 0, b < 0: slipping) the tip slides without sticking: no IWC
    slipping = df[df["p_plus"] > 0]
    assert len(slipping) >= 1 and slipping["status"].isin(["outside", "no return"]).all()
    assert not slipping["iwc"].astype(bool).any() and f"0 of {len(slipping)} with p_plus >= 0" in r.stdout


DRAWS = ["--set", "theta1=-1.6:-0.4", "--set", "theta2=-1.6:-0.4", "--set", "mu=0.3:2", "--solve", "H",
         "--eps", "1e-5:1e-4:log", "--v0", "0.2", "--seed", "7"]


@pytest.mark.parametrize("interface,n", [("ME", 24), ("CS", 8)])
def test_the_arms_random_draws_stick_exactly_where_the_theory_says(tmp_path, interface, n):
    """Random draws over the arm's configuration, friction and compliance: the tip is put on the floor by
    solving H (checked on the numpy arm's kinematics); where p_plus < 0 and b < 0 (Theorem 1) the tip
    sticks and comes back with w/v0 = e; where p_plus >= 0 it never sticks. The rows are the draws
    numpy's default_rng([seed, id]) makes, whatever the interface."""
    out, png = tmp_path / "arm.csv", tmp_path / "map.png"
    r = run("sweep", "--fmu", built_fmu("TwoLinkArm.fmu"), *DRAWS, "--random", n, "--interface", interface,
            "--out", out, "--map", png, check_rc=0)
    df = pd.read_csv(out)
    assert list(df["id"]) == list(range(n)) and png.stat().st_size > 10_000
    for row in df.itertuples():
        u = np.random.default_rng([7, row.id]).random(5)
        assert (row.theta1, row.theta2, row.mu) == pytest.approx((-1.6 + 1.2 * u[0], -1.6 + 1.2 * u[1], 0.3 + 1.7 * u[2]),
                                                                  rel=1e-15)
        assert row.epsilon == pytest.approx(1e-5 * 10 ** u[3], rel=1e-12)
        arm = fmu_arm(row.mu).with_(H=row.start_H)
        assert tip(arm, (row.theta1, row.theta2))[1] == pytest.approx(0, abs=1e-12)
        numpy = coefficients(arm, np.array([row.theta1, row.theta2]), np.array([row.start_omega1, row.start_omega2]))
        assert row.p_plus == pytest.approx(numpy["p_plus"], rel=1e-9) and row.b == pytest.approx(numpy["b"], rel=1e-9)
    assert (df["status"] != "failed").all()
    theorem1 = (df["p_plus"] < 0) & (df["b"] < 0)
    assert theorem1.sum() >= n // 8 and (~theorem1).sum() >= n // 8           # both sides of the map drawn
    assert df.loc[theorem1, "iwc"].astype(bool).all() and (df.loc[theorem1, "status"] == "ok").all()
    # Away from the paradox's edge p_+ = 0, where the theory's O(1) normal force fails (the slip's
    # quasi-static F_N = -b/p_+ grows without bound, and friction can stop the slip on the contact's own
    # time scale): no stick for p_+ > 0, and w/v0 = e for Theorem 1 up to what the O(1) forces do over the
    # IWC, whose duration is eps ln(1/eps)/lambda_+ (eq TT; lambda_+ the root of lambda^2 + delta p_+ lambda
    # + p_+ = 0, delta = 1), relative to v0.
    clear = np.abs(df["p_plus"]) > 0.1
    assert not df.loc[clear & (df["p_plus"] > 0), "iwc"].astype(bool).any()
    stuck = df[theorem1 & clear]
    eps, p = stuck["epsilon"].to_numpy(), stuck["p_plus"].to_numpy()
    duration = eps * np.log(1 / eps) / ((-p + np.sqrt(p * p - 4 * p)) / 2)
    assert np.all(np.abs(stuck["w"] / stuck["v0"] / stuck["e"] - 1) <= 10 * duration / stuck["v0"])
    assert (df.loc[clear, "predicts_iwc"].astype(bool) == df.loc[clear, "iwc"].astype(bool)).all()
    assert "the theory's prediction met in" in r.stdout


def test_a_body_sweep_option_is_refused_for_the_rod(tmp_path):
    r = run("sweep", "--fmu", built_fmu("PainleveRod.fmu"), "--solve", "H", "--out", tmp_path / "x.csv")
    assert r.returncode == 2 and "--solve" in one_line_error(r)
    assert not (tmp_path / "x.csv").exists()


@pytest.mark.parametrize("args,option", [(["--theta0", "0.5:1:3"], "--theta0"), (["--alpha", "2"], "--alpha")])
def test_a_rod_sweep_option_is_refused_for_a_body(tmp_path, args, option):
    r = run("sweep", "--fmu", built_fmu("TwoLinkArm.fmu"), *GRID, *args, "--out", tmp_path / "x.csv")
    assert r.returncode == 2 and option in one_line_error(r)
    assert not (tmp_path / "x.csv").exists()


def test_the_arms_sweep_takes_the_rods_way_through_dask_and_resumes(tmp_path):
    """One sweep for every body: the arm's grid on two dask workers in chunks of 2 gives the serial sweep's
    rows exactly, and its Parquet output, cut to its first part, resumes with the same command to the same
    rows, each case once; every row that ran meets Theorem 1 (w/v0 = e at eps = 1e-5) or is outside it."""
    serial, parallel = tmp_path / "serial.csv", tmp_path / "dask.parquet"
    r = run("sweep", "--fmu", built_fmu("TwoLinkArm.fmu"), *GRID, "--serial", "--out", serial, check_rc=0)
    assert "9 cases" in r.stdout
    args = ["sweep", "--fmu", built_fmu("TwoLinkArm.fmu"), *GRID, "--workers", 2, "--batch", 2, "--out", parallel]
    r = run(*args, check_rc=0)
    assert "local cluster with 2 worker(s)" in r.stderr
    a, b = rows(serial), rows(parallel)
    pd.testing.assert_frame_equal(a, b, check_exact=True)
    parts = sorted(parallel.glob("part-*.parquet"))
    assert len(parts) == 5                        # 9 cases in chunks of 2
    for part in parts[1:]:
        part.unlink()
    r = run(*args, check_rc=0)
    assert "resuming" in r.stderr and "2 of 9 cases already done" in r.stderr
    c = rows(parallel)
    assert list(c["id"]) == list(range(9))
    pd.testing.assert_frame_equal(a, c, check_exact=True)
    ok = a[a["status"] == "ok"]
    assert len(ok) >= 4 and (ok["w"] / ok["v0"]).to_numpy() == pytest.approx(ok["e"].to_numpy(), rel=5e-3)


def rows(out):
    """A body's sweep's rows as the CLI reads them back (sweep.store, typed as sweep.body writes them)."""
    from painleve.sweep.body import typed
    from painleve.sweep.store import ResultStore
    return typed(ResultStore(out).read(None))


def test_a_body_sweeps_cases_run_through_the_body_runner(monkeypatch):
    """sweep.run's batch of a BodySweep: every case that finds a start on the floor is Body.run's, with the
    prediction at its start attached, so the row's w_error is w/v0 - e of theory.general there."""
    from painleve.fmu.body import Body
    from painleve.sweep.body import BodySweep, axes_of
    from painleve.sweep.run import FmuBlob, _close_bodies, run_batch
    seen = []
    run_ = Body.run

    def recorded(body, case, predicted=None, **kwargs):
        outcome = run_(body, case, predicted, **kwargs)
        seen.append(outcome)
        return outcome
    monkeypatch.setattr(Body, "run", recorded)
    spec = BodySweep(axes=axes_of({"theta1": "-1.25,-1.2", "mu": "1,2"}, {"epsilon": "1e-5", "v0": "0.2"}),
                     guess=(("theta2", -1.3),))
    try:
        df = run_batch(spec, np.arange(spec.total), FmuBlob.read(built_fmu("TwoLinkArm.fmu")))
    finally:
        _close_bodies()
    ran = df[df["status"].isin(["ok", "outside"])]
    assert len(seen) == len(ran) == 4 and all(o.prediction is not None for o in seen)
    for row, outcome in zip(ran.itertuples(), seen):
        assert outcome.case.given == (("theta1", row.theta1), ("mu", row.mu))
        assert row.w_error == row.w / row.v0 - row.e and row.e == outcome.prediction.e
    # the columns every chunk writes hold every start value a case solved or set beside its axes
    solved = [f"start_{k}" for k in seen[0].prediction.start if k not in ("theta1", "mu", "epsilon", "v0")]
    assert "start_theta2" in solved and [c for c in df.columns if c.startswith("start_")] == solved
