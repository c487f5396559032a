# SPDX-License-Identifier: BSD-2-Clause
"""The native Model Exchange driver (bench/native/painleve_native_me: the FMU under
SUNDIALS CVODE, no Python in the loop) against the paper and against fmpy.

- Theorem 1: w/v0 at the return to y = 0 is e(delta, theta0) + O(eps ln 1/eps);
  the bound 3 eps ln(1/eps) is the one test_second_importer.py uses.
- fmpy's ME fast loop (painleve.fmu.experiment.Experiment) sets CVODE up the same way
  (BDF, Newton, dense, DQ Jacobian, abstol = rtol * nominal, max step horizon/50)
  with the same rtol, so the two differ by the solvers' global errors only: each
  controls its local error to rtol (relative) and rtol * nominal (absolute) over
  the IWC's ~150 steps; measured apart by at most 3 rtol in w, phi, v and
  t_return/t_return. They are not bit-identical: fmpy bundles SUNDIALS 7, the
  driver links Debian's 6.4. The test allows 10 rtol.
- The analytic Jacobian (fmi2GetDirectionalDerivative) changes only Newton's
  iteration matrix, so the result moves within the same tolerance (measured: 2 rtol).
"""
import math
import shutil
import subprocess
import sys

import numpy as np
import pytest
from fmpy import extract

from painleve.theory import analytic as an
from painleve.experiments.case import Case
from painleve.fmu.experiment import Experiment
from conftest import ROOT

sys.path.insert(0, str(ROOT / "bench"))
from native_driver import case_line, run_native  # noqa: E402

EXECUTABLE = ROOT / "build" / "bench" / "native" / "painleve_native_me"
SOLVER_TOLERANCES = 10      # in units of rtol: see the module docstring


@pytest.fixture(scope="module")
def native():
    if not EXECUTABLE.exists():
        pytest.fail(f"{EXECUTABLE} is missing: `cmake --build build` builds it (CMake builds it only where "
                    f"SUNDIALS CVODE, Debian's libsundials-dev, is found)")
    return str(EXECUTABLE)


@pytest.fixture(scope="module")
def fmu_dir(fmu_path, tmp_path_factory):
    return extract(fmu_path, str(tmp_path_factory.mktemp("fmu")))


def wedge_points(alpha, mu, n=3):
    t1, t2 = an.theta_1(alpha=alpha, mu=mu), an.theta_2(alpha=alpha, mu=mu)
    return [float(t) for t in t1 + (t2 - t1) * np.linspace(0.15, 0.85, n)]


EPSILONS = [1e-3, 1e-4]
THEOREM1 = [Case(epsilon=eps) for eps in EPSILONS] + \
           [Case(theta0=th, delta=delta, epsilon=eps)
            for th in wedge_points(3.0, 3.0) for delta in (0.0, 0.5, 2.0) for eps in EPSILONS]


def rtol_of(case):
    return min(1e-6, case.epsilon / 100)


@pytest.fixture(scope="module")
def native_rows(native, fmu_dir):
    return run_native(native, fmu_dir, THEOREM1)


@pytest.fixture(scope="module")
def fmpy_outcomes(fmu_path):
    with Experiment(fmu_path) as experiment:
        return [experiment.run(case) for case in THEOREM1]


def test_the_cases_are_theorem_1_cases():
    for case in THEOREM1:
        case.check()
        assert an.predict(case).theorem == 1 and an.quadrant(case.theta0, case.phi0, alpha=case.alpha, mu=case.mu) == "inconsistent"


@pytest.mark.parametrize("i", range(len(THEOREM1)), ids=[f"theta0={c.theta0:.3f}-delta={c.delta}-eps={c.epsilon:g}"
                                                          for c in THEOREM1])
def test_theorem1_w_over_v0_is_e_within_eps_ln_1_over_eps(native_rows, i):
    case, row = THEOREM1[i], native_rows[i]
    assert row["case"] is case and row["iwc"]
    assert row["epsilon"] == case.epsilon and row["rtol"] == rtol_of(case)
    bound = 3 * case.epsilon * math.log(1 / case.epsilon)
    assert abs(row["w"] / case.v0 - an.predict(case).e) < bound, row
    assert abs(row["theta"] - case.theta0) < bound and abs(row["v"]) < bound, row
    assert 0 < row["t_return"] < 20 * an.predict(case).time_scale, row


def test_native_agrees_with_fmpys_fast_loop_to_the_solver_tolerance(native_rows, fmpy_outcomes):
    for case, row, o in zip(THEOREM1, native_rows, fmpy_outcomes):
        tol = SOLVER_TOLERANCES * rtol_of(case)
        assert row["iwc"] == o.iwc
        for name in ("w", "v", "theta", "phi"):
            assert abs(row[name] - getattr(o, name)) <= tol * max(1.0, abs(getattr(o, name))), (name, row, o)
        assert row["t_return"] == pytest.approx(o.t_return, rel=tol), (row, o)
        # Outcome.events stops before the return's own event unless delta = 0 (lift-off and return are one)
        assert row["nevents"] == o.events + (case.delta > 0), (row, o)


@pytest.mark.parametrize("rtol", [1e-10])
def test_at_a_tight_tolerance_native_and_fmpy_converge_to_one_answer(native, fmu_dir, fmu_path, rtol):
    """Not only near each other at the harness's rtol: as rtol -> 0 both tend to the same
    solution, so they integrate the same model with the same event semantics."""
    cases = [THEOREM1[0], THEOREM1[4], THEOREM1[8]]
    rows = run_native(native, fmu_dir, cases, rtol=rtol)
    with Experiment(fmu_path, relative_tolerance=rtol) as experiment:
        outcomes = [experiment.run(case) for case in cases]
    for row, o in zip(rows, outcomes):
        for name in ("w", "v", "theta", "phi"):
            assert abs(row[name] - getattr(o, name)) <= SOLVER_TOLERANCES * rtol, (name, row, o)
        assert row["t_return"] == pytest.approx(o.t_return, rel=SOLVER_TOLERANCES * rtol)


def test_analytic_and_difference_quotient_jacobians_agree(native, fmu_dir, native_rows):
    analytic = run_native(native, fmu_dir, THEOREM1, jacobian="analytic")
    for case, dq, an_row in zip(THEOREM1, native_rows, analytic):
        tol = SOLVER_TOLERANCES * rtol_of(case)
        for name in ("w", "v", "theta", "phi"):
            assert abs(an_row[name] - dq[name]) <= tol * max(1.0, abs(dq[name])), (name, dq, an_row)
        assert an_row["t_return"] == pytest.approx(dq["t_return"], rel=tol)
        # the DQ Jacobian costs nx = 6 right-hand sides per evaluation; the analytic one none
        assert dq["nfev"] > an_row["nfev"] and an_row["njev"] > 0


def test_repeat_rtol_and_a_zipped_fmu(native, fmu_path):
    case = Case(epsilon=1e-3)
    once, thrice = (run_native(native, fmu_path, [case], rtol=1e-8, repeat=r)[0] for r in (1, 3))
    assert once["rtol"] == 1e-8
    for name in ("w", "phi", "t_return", "nsteps", "nfev", "ngev", "nevents"):
        assert once[name] == thrice[name]       # deterministic: the instance is reset between runs
    assert thrice["wall_seconds"] > 0 and thrice["peak_rss_kib"] > 0
    assert once["nsteps"] > 0 and once["ngev"] > 0 and once["nevents"] == 4


def _run(native, target, stdin, *args):
    return subprocess.run([native, str(target), *args], input=stdin, capture_output=True, text=True, timeout=60)


@pytest.mark.parametrize("line, words", [
    ("1 0.5 one 1 1e-3 0 3 3", "v0 = 'one' is not a number"),
    ("1 0.5 1 1 1e-3 0 3", "7 numbers given, 8 needed"),
    ("1 0.5 1 1 1e-3 0 3 3 9", "more than 8 fields"),
    ("1 0.5 1 1 inf 0 3 3", "epsilon = 'inf' is not a finite"),
])
def test_an_unparsable_line_is_refused_with_its_line_number(native, fmu_dir, line, words):
    done = _run(native, fmu_dir, f"{case_line(Case())}\n{line}\n")
    assert done.returncode == 2 and "line 2" in done.stderr and words in done.stderr, done.stderr
    assert done.stdout == ""      # nothing runs before all input is read


@pytest.mark.parametrize("case, words", [
    (Case(epsilon=2.0), "fmi2SetReal failed: epsilon = 2 is out of range"),
    (Case(alpha=-1.0), "fmi2SetReal failed: alpha = -1 is out of range"),
    (Case(theta0=1.5), "outside the Painleve wedge"),
])
def test_a_value_the_fmu_or_the_driver_refuses_raises_with_the_reason(native, fmu_dir, case, words):
    with pytest.raises(RuntimeError, match=words):
        run_native(native, fmu_dir, [case])


def test_a_failed_run_reports_the_reason(native, fmu_dir):
    # eps delta = 0.1: outside the asymptotic regime the rod does not come back up within the
    # horizon (test_theorems_on_fmu.py)
    with pytest.raises(RuntimeError, match=r"did not come back to y = 0 .*asymptotic regime\? eps \* delta = 0.1"):
        run_native(native, fmu_dir, [Case(theta0=0.5908, delta=10.0, epsilon=1e-2)])


def test_a_library_that_does_not_load_or_lacks_fmi2_is_named(native, fmu_dir, tmp_path):
    for name, content in (("junk", b"not a shared library"), ("other", None)):
        target = tmp_path / name
        (target / "binaries" / "linux64").mkdir(parents=True)
        shutil.copy(f"{fmu_dir}/modelDescription.xml", target)
        library = target / "binaries" / "linux64" / "PainleveRod.so"
        if content is None:       # a real shared library without the fmi2* functions: this process's libm
            libm = next(line.split()[-1] for line in open("/proc/self/maps") if "/libm.so" in line)
            shutil.copy(libm, library)
        else:
            library.write_bytes(content)
        done = _run(native, target, case_line(Case()) + "\n")
        assert done.returncode == 1, done.stderr
        assert ("dlopen failed" if content else "does not export fmi2") in done.stderr, done.stderr
    done = _run(native, ROOT / "no-such-fmu", case_line(Case()) + "\n")
    assert done.returncode == 1 and "No such file or directory" in done.stderr
    done = _run(native, fmu_dir, "", "--jacobian", "exact")
    assert done.returncode == 2 and "give dq or analytic" in done.stderr


@pytest.mark.skipif(shutil.which("valgrind") is None, reason="valgrind is not installed (run.sh installs it)")
@pytest.mark.parametrize("stdin", [case_line(Case()) + "\n", case_line(Case(epsilon=2.0)) + "\n"],
                         ids=["run", "refused"])
def test_valgrind_finds_no_leak_or_error(native, fmu_dir, stdin):
    done = subprocess.run(["valgrind", "-q", "--leak-check=full", "--errors-for-leak-kinds=all",
                           "--error-exitcode=99", native, fmu_dir, "--jacobian", "analytic"],
                          input=stdin, capture_output=True, text=True, timeout=120)
    assert done.returncode in (0, 1) and "==" not in done.stderr, done.stderr
