# SPDX-License-Identifier: BSD-2-Clause
"""The `painleve` command run as a user runs it (a subprocess, tests/helpers/cli_run.py), with
what it wrote checked: iwc, validate (on the built FMU and on one built with a wrong physics
constant), figures (their points on the analytic curves), and bad input in one line. The
sweep command: test_cli_sweep.py."""
import json
import math
import os
import pathlib
import re
import shutil
import subprocess
import sys

import pytest

from painleve.theory import analytic as an
from conftest import ROOT
from helpers.cli_run import one_line_error, run


# ------------------------------------------------------------------ help
@pytest.mark.parametrize("command, options", [
    ([], ["iwc", "validate", "figures", "sweep"]),
    (["iwc"], ["--theta0", "--phi0", "--v0", "--delta", "--eps", "--w10", "--alpha", "--mu", "--kappa", "--beta",
               "--fmu", "--interface", "--json"]),
    (["validate"], ["FMU", "--interface", "--sample", "--kappa", "--beta", "--report", "--json"]),
    (["figures"], ["--fmu", "--out", "--only", "--dpi"]),
    (["sweep"], ["--theta0", "--phi0", "--delta", "--eps", "--v0", "--w10", "--alpha", "--mu", "--kappa", "--beta",
                 "--random", "--seed",
                 "--out", "--scheduler", "--workers", "--batch", "--serial", "--fmu", "--no-progress", "lo:hi:n"]),
])
def test_help_explains_every_option(command, options):
    r = run(*command, "--help", check_rc=0)
    for option in options:
        assert option in r.stdout, f"{option} missing from `painleve {' '.join(command)} --help`"


# ------------------------------------------------------------------ iwc
def test_iwc_prints_the_simulated_outcome_beside_the_analytic_one(fmu_path):
    r = run("iwc", "--fmu", fmu_path, "--theta0", 1.0, "--phi0", 0.5, "--eps", 1e-5, check_rc=0)
    e = an.e_integrated(1.0, 1.0)     # exact integration of the sticking system, not the closed form
    row = next(line for line in r.stdout.splitlines() if line.startswith("w at return"))
    simulated, analytic = (float(cell.split()[0]) for cell in re.split(r"\s{2,}", row)[1:3])
    assert analytic == pytest.approx(e, rel=1e-6)
    assert simulated == pytest.approx(e, rel=1e-3)
    assert "Theorem 1" in r.stdout and "IWC" in r.stdout


def test_iwc_with_a_nonlinear_compliance_law_compares_with_its_rigid_limit(fmu_path):
    # --kappa, --beta reach the FMU, and the analytic column is the law's e (painleve.theory.rigid_limit),
    # which the simulated w approaches as for the linear law, not the linear e.
    from painleve.theory import rigid_limit
    r = json.loads(run("iwc", "--fmu", fmu_path, "--theta0", 0.9, "--phi0", 0.5, "--eps", 1e-6, "--kappa", 2,
                       "--beta", 2, "--json", check_rc=0).stdout)
    e_law, e_linear = rigid_limit.e(1.0, 0.9, kappa=2.0, beta=2.0), an.e(1.0, 0.9)
    assert r["predicted"]["e"] == pytest.approx(e_law, rel=1e-10)
    assert r["simulated"]["w"] == pytest.approx(e_law, rel=1e-3) and abs(r["simulated"]["w"] - e_linear) > 0.01 * e_linear


def test_iwc_json_on_both_sides_of_the_separatrix(fmu_path):
    state = ["--theta0", 0.9463, "--phi0", 1.6654, "--eps", 1e-5]
    w1s = an.w1_star(0.9463, 1.6654, 1.0)
    below = json.loads(run("iwc", "--fmu", fmu_path, *state, "--w10", 1.5 * w1s, "--json", check_rc=0).stdout)
    above = json.loads(run("iwc", "--fmu", fmu_path, *state, "--w10", 0.5 * w1s, "--json", check_rc=0).stdout)
    assert below["predicted"]["theorem"] == 2 and below["predicted"]["w1_star"] == pytest.approx(w1s)
    assert below["simulated"]["iwc"] and below["simulated"]["w"] == pytest.approx(an.e_integrated(1.0, 0.9463),
                                                                                  rel=0.01)
    assert not above["simulated"]["iwc"] and 0 < above["simulated"]["w"] < 5e-5      # w = O(eps)


@pytest.mark.parametrize("args, words", [
    (["iwc", "--gamma", "3"], ["--gamma", "painleve iwc --help"]),
    (["iwc", "--eps", "0"], ["eps", "small positive"]),
    (["iwc", "--eps", "-1e-3"], ["eps", "small positive"]),
    (["iwc", "--fmu", "/nonexistent/PainleveRod.fmu"], ["no FMU at /nonexistent", "run.sh"]),
    (["iwc", "--theta0", "1.5"], ["p_+", "choose --theta0 inside the Painleve wedge"]),
    (["iwc", "--mu", "1"], ["mu_P", "raise --mu"]),
    (["iwc", "--theta0", "0.9463", "--phi0", "1.6654"], ["w10", "give --w10 < 0"]),
    (["iwc", "--v0", "-1"], ["v0", "give --v0 > 0"]),
    (["sweep", "--gamma", "1:2:3"], ["--gamma"]),
    (["sweep", "--eps", "0:1e-3:3"], ["--eps", "[1e-8, 1]"]),
    (["sweep", "--theta0", "0.5:1.4"], ["lo:hi:n"]),
    (["figures", "--only", "nope"], ["GB, eDelta0, video"]),
    (["validate", "/nonexistent/PainleveRod.fmu"], ["no FMU at /nonexistent"]),
])
def test_bad_input_ends_in_one_line_that_says_what_to_change(fmu_path, args, words):
    if "--fmu" not in args and args[0] in ("iwc", "sweep", "figures"):
        args = args + ["--fmu", fmu_path]
    r = run(*args)
    assert r.returncode == 2, r.stderr
    line = one_line_error(r)
    for word in words:
        assert word in line


def test_a_file_that_is_not_an_fmu_is_named(tmp_path):
    bogus = tmp_path / "PainleveRod.fmu"
    bogus.write_text("not a zip")
    assert "is not an FMU" in one_line_error(run("validate", bogus))


# ------------------------------------------------------------------ validate
def test_validate_passes_on_the_built_fmu_and_writes_its_report(fmu_path, tmp_path):
    report = tmp_path / "validation.md"
    r = run("validate", fmu_path, "--report", report, check_rc=0)
    assert "FAIL" not in r.stdout
    checks = [line for line in r.stdout.splitlines() if line.startswith("PASS")]
    kinds = {line.split()[1].split("/")[0] for line in checks}
    assert kinds == {"static", "default", "theorem1", "theorem2", "separatrix"}
    assert len(checks) > 50 and f"all {len(checks)} checks passed" in r.stdout
    assert report.read_text().count("| PASS |") == len(checks)


@pytest.fixture(scope="module")
def wrong_physics_fmu(tmp_path_factory):
    """The FMU built from this tree with the Filippov coefficient of w' while sticking,
    S_w = G_NN - G_TN^2/G_TT (eq Sw; for the rod (1 + alpha)/k), replaced by S_w + 1/G_TT
    (for the rod (2 + alpha)/k), in the contact core's sticking field (w is the body's
    second velocity)."""
    src = tmp_path_factory.mktemp("wrong")
    for name in ("CMakeLists.txt", "modelDescription.xml", "LICENSE"):
        shutil.copy(ROOT / name, src / name)
    for folder in ("fmu_src", "cmake"):
        shutil.copytree(ROOT / folder, src / folder)
    core = src / "fmu_src" / "contact" / "contact.c"
    text = core.read_text()
    right = "dx[b->velocity[i]] = s.free[i] + s.normal[i] * F - s.friction[i] * F_T;"
    if right not in text:
        pytest.fail(f"contact.c no longer contains {right!r}: update the wrong-physics patch of this test")
    core.write_text(text.replace(right, "dx[b->velocity[i]] = s.free[i] + (s.normal[i] + (i == 1) / s.G_TT) * F"
                                        " - s.friction[i] * F_T;"))
    cmake = shutil.which("cmake", path=str(pathlib.Path(sys.executable).parent) + os.pathsep + os.environ["PATH"])
    build = src / "build"
    for cmd in ([cmake, "-S", src, "-B", build, f"-DPython3_EXECUTABLE={sys.executable}"],
                [cmake, "--build", build, "-j", "2"]):
        r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True)
        assert r.returncode == 0, r.stdout + r.stderr
    return str(build / "PainleveRod.fmu")


def test_validate_fails_on_an_fmu_with_a_wrong_physics_constant_naming_the_cases(wrong_physics_fmu, tmp_path):
    report = tmp_path / "validation.json"
    r = run("validate", wrong_physics_fmu, "--report", report)
    assert r.returncode == 1, r.stdout + r.stderr
    failed = [line.split()[1] for line in r.stdout.splitlines() if line.startswith("FAIL")]
    # it is a valid FMU with the right interface; what fails is the physics
    assert not any(name.startswith(("static", "default")) for name in failed)
    assert "theorem1/ME/wide-f0.5-d1" in failed and "theorem2/ME/video/below" in failed
    summary = r.stdout.strip().splitlines()[-1]
    assert "FAILED" in summary and "theorem1/ME/wide-f0.2-d0" in summary
    data = json.loads(report.read_text())
    assert not data["passed"] and set(data["failed"]) == set(failed)
    worst = max(abs(c["numbers"]["w_rel_errors"][-1]) for c in data["checks"] if c["id"] in failed
                and c["id"].startswith("theorem1"))
    assert worst > 0.02       # the error no longer falls with eps: percents at eps = 1e-6


# ------------------------------------------------------------------ figures
@pytest.fixture(scope="module")
def figures(fmu_path, tmp_path_factory):
    out = tmp_path_factory.mktemp("figures")
    r = run("figures", "--fmu", fmu_path, "--out", out, "--dpi", 80, check_rc=0)
    return out, r.stdout.split()


def test_figures_are_written_as_pngs(figures):
    import matplotlib.image
    out, printed = figures
    for name in ("fig_GB.png", "fig_eDelta0.png", "fig_video.png", "fig_eLaw.png"):
        assert str(out / name) in printed
        image = matplotlib.image.imread(out / name)
        assert image.shape[0] > 300 and image.shape[1] > 500 and image.std() > 0.05
    summary = (out / "figures.md").read_text()
    assert "(fig_GB.png)" in summary and "fig:" not in summary       # no LaTeX labels in what a user reads


def test_fig_gb_points_lie_in_the_analytic_quadrants(figures):
    gb = json.loads((figures[0] / "figures.json").read_text())["GB"]
    for q in gb["points"]:
        b = -1 + q["phi"] ** 2 * math.sin(q["theta"])
        s, c = math.sin(q["theta"]), math.cos(q["theta"])
        p = 1 + 3 * c * c - 1.4 * 3 * s * c
        expected = {(True, True): "indeterminate", (True, False): "lift-off", (False, False): "slipping",
                    (False, True): "inconsistent"}[(b > 0, p < 0)]
        assert q["analytic"] == expected
        if abs(b) > 0.02 and abs(p) > 0.02:     # away from the lines b = 0 and p_+ = 0
            assert q["simulated"] == expected, q
    assert gb["agreement"] > 0.95


def test_fig_edelta0_points_lie_on_the_curves_and_approach_them_as_eps_falls(figures):
    d = json.loads((figures[0] / "figures.json").read_text())["eDelta0"]
    for q in d["a"]:
        assert q["e_analytic"] == pytest.approx(an.e_integrated(0.0, q["theta0"], alpha=3, mu=1.4), rel=1e-7)
    fine = {q["theta0"]: q for q in d["a"] if q["epsilon"] == 1e-6}
    coarse = {q["theta0"]: q for q in d["a"] if q["epsilon"] == 1e-4}
    for theta0, q in fine.items():
        assert abs(q["rel_error"]) < 0.015
        assert abs(q["rel_error"]) < abs(coarse[theta0]["rel_error"])
    for q in d["b"]:
        assert q["e_analytic"] == pytest.approx(an.e_integrated(q["delta"], q["theta0"], alpha=3, mu=1.4),
                                                rel=1e-7)
        assert abs(q["rel_error"]) < 0.01


def test_fig_video_one_rod_undergoes_iwc_and_the_other_lifts_off(figures):
    v = json.loads((figures[0] / "figures.json").read_text())["video"]
    green, blue = v["rods"]["green"], v["rods"]["blue"]
    eps = v["params"]["epsilon"]
    assert v["separation_at_t0"] == pytest.approx(1e-3, rel=1e-6)
    for rod in (green, blue):    # both graze at t = 0.5 in the paper's state
        assert rod["touch"]["time"] == pytest.approx(0.5, abs=1e-5)
        assert rod["touch"]["theta"] == pytest.approx(0.9463, abs=1e-5)
        assert rod["touch"]["v"] == pytest.approx(1.0, abs=1e-5)
    assert green["touch"]["w"] < eps * v["w1_star"] < blue["touch"]["w"] < 0
    e = an.e_integrated(1.0, 0.9463)
    p, q = an.p_plus(0.9463), an.q_plus(0.9463)
    assert green["iwc"] and green["w_return"] == pytest.approx(e * green["touch"]["v"], rel=0.03)
    assert green["min_w"] == pytest.approx(-p / q * green["touch"]["v"], rel=0.03)     # eq z2EpsPi2
    assert not blue["iwc"] and 0 < blue["w_return"] < eps
    assert green["y_at_t_end"] > blue["y_at_t_end"] + 0.05      # clearly apart at t = 1
