# SPDX-License-Identifier: BSD-2-Clause
"""`painleve sweep` on a body FMU (sweep.body): the arm's grid over theta1 and mu, each row's theory
checked against the independent numpy arm (helpers.arm_lagrange) and its simulation against Theorem 1;
a rod option the body's sweep cannot honour is refused."""
import numpy as np
import pandas as pd
import pytest

from conftest import built_fmu
from helpers.arm_lagrange import Arm, coefficients
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


@pytest.mark.parametrize("args,option", [(["--theta0", "0.5:1:3"], "--theta0"), (["--random", "5"], "--random"),
                                         (["--workers", "2"], "--workers")])
def test_a_rod_sweep_option_is_refused_for_a_body(tmp_path, args, option):
    r = run("sweep", "--fmu", built_fmu("TwoLinkArm.fmu"), *GRID, *args, "--out", tmp_path / "x.csv")
    assert r.returncode == 2 and option in one_line_error(r)
    assert not (tmp_path / "x.csv").exists()
