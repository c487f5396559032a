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


@pytest.mark.parametrize("args,option", [(["--theta0", "0.5:1:3"], "--theta0"), (["--batch", "5"], "--batch"),
                                         (["--workers", "2"], "--workers")])
def test_a_rod_sweep_option_is_refused_for_a_body(tmp_path, args, option):
    r = run("sweep", "--fmu", built_fmu("TwoLinkArm.fmu"), *GRID, *args, "--out", tmp_path / "x.csv")
    assert r.returncode == 2 and option in one_line_error(r)
    assert not (tmp_path / "x.csv").exists()
