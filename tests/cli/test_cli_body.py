# SPDX-License-Identifier: BSD-2-Clause
"""`painleve iwc`, `validate` and `figures` through the generic body path (cli.body), on the rod
FMUs with --set: the FMU's outputs alone must give the rod's known e, wedge and a passing validation."""
import json

import numpy as np
import pytest

from conftest import built_fmu
from helpers.cli_run import one_line_error, run
from painleve.theory import analytic as A

ROD = ["--set", "theta=1.0", "--set", "phi=0.5", "--set", "x=0"]


def test_iwc_on_the_rod_through_the_body_path_gives_its_e():
    r = run("iwc", "--fmu", built_fmu("PainleveRod.fmu"), *ROD, "--eps", "1e-4", "--delta", "0.5", "--json",
            check_rc=0)
    out = json.loads(r.stdout)
    e = A.e(0.5, 1.0)
    assert out["predicted"]["e"] == pytest.approx(e, rel=1e-12)
    assert out["predicted"]["quadrant"] == "inconsistent" and out["simulated"]["iwc"]
    assert out["simulated"]["w"] == pytest.approx(e, rel=2e-3)          # v0 = 1
    assert out["start"]["y"] == 0 and out["start"]["v"] == 1.0


def test_iwc_on_the_si_rod_sets_eps_and_delta_through_k_and_c():
    r = run("iwc", "--fmu", built_fmu("PainleveRodSI.fmu"), "--set", "theta=0.9", "--set", "phi=1.5", "--set", "x=0",
            "--v0", "2", "--eps", "1e-5", "--delta", "2", "--json", check_rc=0)
    out = json.loads(r.stdout)
    e = A.e(2.0, 0.9)
    assert out["predicted"]["e"] == pytest.approx(e, rel=1e-9)
    assert out["simulated"]["w"] / 2.0 == pytest.approx(e, rel=2e-3)


def test_the_table_names_the_body_and_the_theorem():
    r = run("iwc", "--fmu", built_fmu("PainleveRod.fmu"), *ROD, "--eps", "1e-3", check_rc=0)
    assert "generic body path" in r.stdout and "Theorem 1 applies" in r.stdout and "w/v0 at return" in r.stdout


def test_validate_on_the_rod_through_the_body_path_passes():
    r = run("validate", "--fmu", built_fmu("PainleveRod.fmu"), *ROD, "--json", check_rc=0)
    out = json.loads(r.stdout)
    assert out["passed"] and len(out["checks"]) == 2 + 2 * 4      # the start; three eps and the trend, ME and CS
    for interface in ("ME", "CS"):
        errors = next(c for c in out["checks"] if c["id"] == f"body/{interface}/all/convergence")["numbers"]["errors"]
        assert errors[-1] < errors[0] / 10


def test_validate_outside_the_paradox_fails_naming_it():
    r = run("validate", "--fmu", built_fmu("PainleveRod.fmu"), "--set", "theta=2.0", "--set", "phi=0.5",
            "--set", "x=0", "--json", check_rc=1)
    out = json.loads(r.stdout)
    assert "p_+ < 0" in next(c for c in out["checks"] if c["id"].endswith("paradox"))["measured"]


def test_the_paradox_region_of_the_rod_is_its_wedge(tmp_path):
    run("figures", "--fmu", built_fmu("PainleveRod.fmu"), "--set", "phi=0.5", "--out", tmp_path, "--points", "401",
        check_rc=0)
    data = json.loads((tmp_path / "paradox_region.json").read_text())
    assert data["axes"] == ["theta"] and (tmp_path / "paradox_region.png").stat().st_size > 10_000
    th, pp = np.array(data["grids"][0]), np.array(data["p_plus"])
    inside = th[(pp < 0) & (th > 0) & (th < np.pi / 2)]
    h = th[1] - th[0]
    assert inside.min() == pytest.approx(A.theta_1(), abs=h) and inside.max() == pytest.approx(A.theta_2(), abs=h)


@pytest.mark.parametrize("args,words", [(["--set", "theta"], "NAME=VALUE"), (["--set", "theta=x"], "not a finite"),
                                        (["--set", "nosuch=1"], "no variable 'nosuch'")])
def test_bad_body_input_ends_in_one_line(args, words):
    r = run("iwc", "--fmu", built_fmu("PainleveRod.fmu"), *args)
    assert r.returncode == 2 and words in one_line_error(r)


@pytest.mark.parametrize("w10,outcome", [(-0.1, "lift-off"), (-3.0, "IWC")])
def test_theorem_2_through_the_body_path_splits_at_w1_star(w10, outcome):
    """Figure `video`'s grazing state (indeterminate): w1* = -0.4177 (eq w1star); above it lift-off, below IWC."""
    args = ["--set", "theta=0.9463", "--set", "phi=1.6654", "--set", "x=0", "--w10", w10, "--eps", "1e-4"]
    out = json.loads(run("iwc", "--fmu", built_fmu("PainleveRod.fmu"), *args, "--json", check_rc=0).stdout)
    assert out["predicted"]["w1_star"] == pytest.approx(A.w1_star(0.9463, 1.6654, 1.0), rel=1e-9)
    assert out["simulated"]["iwc"] == (outcome == "IWC")
    table = run("iwc", "--fmu", built_fmu("PainleveRod.fmu"), *args, check_rc=0).stdout
    assert next(line for line in table.splitlines() if line.startswith("outcome")).split()[1:] == [outcome, outcome]


@pytest.mark.parametrize("fmu", ["PainleveRod.fmu", "TwoLinkArm.fmu"])
def test_iwc_through_co_simulation_runs_the_fmus_integrator_and_agrees_with_model_exchange(fmu):
    """--interface CS is honoured on the generic path: the run is the FMU's own integrator's (its phases
    from the FMU's record), and its return is Model Exchange's to the solvers' tolerance (eps / 100)."""
    args = ROD if fmu == "PainleveRod.fmu" else []
    me, cs = (json.loads(run("iwc", "--fmu", built_fmu(fmu), *args, "--eps", "1e-3", "--interface", i, "--json",
                             check_rc=0).stdout) for i in ("ME", "CS"))
    assert (me["interface"], cs["interface"]) == ("ME", "CS") and me["simulated"] != cs["simulated"]
    assert cs["simulated"]["iwc"] == me["simulated"]["iwc"] is True
    for k in ("w", "t_return", "stick"):
        assert cs["simulated"][k] == pytest.approx(me["simulated"][k], rel=1e-3)
    if fmu == "PainleveRod.fmu":
        assert cs["simulated"]["w"] == pytest.approx(A.e(1.0, 1.0), rel=2e-2)     # Theorem 1 at eps = 1e-3


@pytest.mark.parametrize("args,option", [(["--theta0", "0.9"], "--theta0"), (["--mu", "2"], "--mu")])
def test_a_rod_option_the_body_path_cannot_honour_is_an_error(args, option):
    r = run("iwc", "--fmu", built_fmu("TwoLinkArm.fmu"), *args)
    assert r.returncode == 2 and option in one_line_error(r) and "--set" in one_line_error(r)


@pytest.mark.parametrize("interface", ["ME", "CS"])
def test_the_rods_own_iwc_takes_the_general_path_and_its_closed_forms_agree(interface):
    """`painleve iwc` without --set runs the rod's Case through the path of every body: the theory from the
    FMU's coefficient outputs (theory.general) must be the rod's closed forms (eq eGeneral at theta0)."""
    out = json.loads(run("iwc", "--fmu", built_fmu("PainleveRod.fmu"), "--theta0", "1.1", "--delta", "2", "--eps",
                         "1e-4", "--interface", interface, "--json", check_rc=0).stdout)
    e = A.e(2.0, 1.1)
    assert out["from_fmu"]["e"] == pytest.approx(e, rel=1e-12) and out["predicted"]["e"] == pytest.approx(e, rel=1e-15)
    assert out["from_fmu"]["coefficients"]["p_plus"] == pytest.approx(A.p_plus(1.1), rel=1e-13)
    assert out["from_fmu"]["quadrant"] == "inconsistent" and out["simulated"]["iwc"]
    assert out["simulated"]["w"] == pytest.approx(e, rel=5e-3)            # v0 = 1, Theorem 1 at eps = 1e-4


@pytest.mark.parametrize("args,option", [(["--v0", "2"], "--v0"), (["--delta", "3"], "--delta")])
def test_a_body_option_the_rods_own_validation_cannot_honour_is_an_error(args, option):
    r = run("validate", *args, "--fmu", built_fmu("PainleveRod.fmu"))
    assert r.returncode == 2 and option in one_line_error(r)


def test_the_rods_own_figures_draw_the_paradox_region_every_body_gets_its_wedge(tmp_path):
    r = run("figures", "--fmu", built_fmu("PainleveRod.fmu"), "--only", "paradox", "--points", "401", "--out", tmp_path,
            check_rc=0)
    assert str(tmp_path / "paradox_region.png") in r.stdout.split() and not (tmp_path / "fig_GB.png").exists()
    data = json.loads((tmp_path / "paradox_region.json").read_text())
    th, pp = np.array(data["grids"][0]), np.array(data["p_plus"])
    inside = th[(pp < 0) & (th > 0) & (th < np.pi / 2)]
    h = th[1] - th[0]
    assert inside.min() == pytest.approx(A.theta_1(), abs=h) and inside.max() == pytest.approx(A.theta_2(), abs=h)


def test_guess_is_refused_where_nothing_is_solved(tmp_path):
    r = run("figures", "--fmu", built_fmu("TwoLinkArm.fmu"), "--guess", "theta2=-1", "--out", tmp_path)
    assert r.returncode == 2 and "--guess" in one_line_error(r)
