# SPDX-License-Identifier: BSD-2-Clause
"""Co-Simulation built against SUNDIALS 7 (Debian 12 ships 6.4): the FMU's
sources, linked statically with the CVODE 7.1.1 that `bash run.sh test` builds
into .tools/sundials-7.1 (from crates.io sundials-sys), give Theorem 1 as the
SUNDIALS 6 build does, and the same numbers to the solver's tolerance."""
import math
import re
import subprocess
import sys

import fmpy
import pytest

from painleve.theory import analytic as an
from painleve.experiments import acceptance
from painleve.experiments.case import Case
from painleve.fmu.experiment import Experiment
from painleve.experiments.studies import convergence
from conftest import ROOT
from test_theorems_on_fmu import THEOREM1_CASES, THEOREM1_DELTAS, assert_theorem1_converges

SUNDIALS7 = ROOT / ".tools" / "sundials-7.1"


def run(cmd):
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True)
    assert r.returncode == 0, f"{' '.join(map(str, cmd))} failed:\n{r.stdout[-4000:]}\n{r.stderr[-4000:]}"
    return r


@pytest.fixture(scope="module")
def build7(tmp_path_factory):
    """The whole project (the FMU and the native driver, warnings as errors) built against SUNDIALS 7."""
    config = SUNDIALS7 / "include" / "sundials" / "sundials_config.h"
    if not config.exists() or not re.search(r"#define SUNDIALS_VERSION_MAJOR 7\b", config.read_text()):
        pytest.fail(f"SUNDIALS 7 is missing from {SUNDIALS7}: `bash run.sh test` builds it there (once)")
    build = tmp_path_factory.mktemp("sundials7") / "build"
    configure = run(["cmake", "-S", ROOT, "-B", build, f"-DSUNDIALS_ROOT={SUNDIALS7}",
                     f"-DPython3_EXECUTABLE={sys.executable}", "-DCMAKE_BUILD_TYPE=Release"])
    assert f"SUNDIALS 7.1.1 CVODE found in {SUNDIALS7}/include" in configure.stdout, configure.stdout
    run(["cmake", "--build", build, "-j", "2"])
    return build


@pytest.fixture(scope="module")
def fmu7(build7):
    return str(build7 / "PainleveRod.fmu")


def binary(fmu, tmp_path):
    return next((fmpy.extract(fmu, tmp_path) / "binaries" / "linux64").glob("*.so"))


def test_the_sundials_7_build_links_sundials_7_statically(fmu7, fmu_path, tmp_path):
    so7, so6 = binary(fmu7, tmp_path / "7"), binary(fmu_path, tmp_path / "6")
    needed = re.findall(r"\(NEEDED\).*\[(.*)\]", run(["readelf", "-d", so7]).stdout)
    assert set(needed) <= {"libc.so.6", "libm.so.6"}, needed
    # The (local) symbol table says which SUNDIALS is inside: the context's error-handler
    # stack is SUNDIALS 7's, CVODE's own error handler SUNDIALS 6's (removed in 7).
    symbols7, symbols6 = (set(run(["nm", so]).stdout.split()) for so in (so7, so6))
    assert "SUNContext_PushErrHandler" in symbols7 and "CVodeSetErrHandlerFn" not in symbols7
    assert "CVodeSetErrHandlerFn" in symbols6 and "SUNContext_PushErrHandler" not in symbols6


@pytest.fixture(scope="module")
def experiments(fmu7, fmu_path):
    with Experiment(fmu7, fmi_type="CoSimulation") as by7, Experiment(fmu_path, fmi_type="CoSimulation") as by6:
        yield by7, by6


@pytest.mark.parametrize("delta", THEOREM1_DELTAS)
@pytest.mark.parametrize("params, epsilons", THEOREM1_CASES)
def test_theorem1_through_cosimulation_on_sundials_7(experiments, params, epsilons, delta):
    case = Case(phi0=0.5, v0=1.0, delta=delta, **params)
    assert an.quadrant(case.theta0, case.phi0, alpha=case.alpha, mu=case.mu) == "inconsistent"
    epsilons = acceptance.in_regime(epsilons, delta)
    by7, by6 = (convergence(x, case, epsilons) for x in experiments)
    assert_theorem1_converges(by7)
    assert_theorem1_converges(by6)
    # Both run at the harness's rtol = min(1e-6, eps/100); the IWC amplifies solver errors
    # (it follows an unstable manifold), so "the same" is within 1000 x that tolerance.
    for eps, a, b in zip(epsilons, by7.outcomes, by6.outcomes):
        rtol = min(1e-6, eps / 100)
        for name in ("w", "phi", "v"):
            assert abs(getattr(a, name) - getattr(b, name)) < 1000 * rtol, (name, eps, by7.table(), by6.table())


@pytest.mark.parametrize("tolerance", [1e-8, 1e-10])
def test_default_experiment_is_the_same_on_sundials_6_and_7(fmu7, fmu_path, tolerance):
    out = ["y", "w", "v", "phi"]
    by7, by6 = (fmpy.simulate_fmu(f, fmi_type="CoSimulation", output=out, relative_tolerance=tolerance)
                for f in (fmu7, fmu_path))
    assert by7["y"][-1] > 0 and by7["w"][-1] > 0     # the rod lifted off: an IWC
    for name in out:
        assert abs(by7[name][-1] - by6[name][-1]) < 1000 * tolerance, name


def test_the_native_driver_builds_and_runs_on_sundials_7(build7, fmu7):
    # bench/native shares sundials_compat.h: Theorem 1 under CVODE 7 as test_native_driver.py checks it.
    sys.path.insert(0, str(ROOT / "bench"))
    from native_driver import run_native
    cases = [Case(epsilon=1e-4), Case(theta0=1.1, delta=2.0, epsilon=1e-5)]
    for case, row in zip(cases, run_native(build7 / "bench" / "native" / "painleve_native_me", fmu7, cases)):
        e = an.predict(case).e
        assert row["iwc"] and abs(row["w"] / case.v0 - e) < 3 * case.epsilon * math.log(1 / case.epsilon), row


CVODE_FAILURE = """
import sys
from fmpy.fmi1 import FMICallException
from painleve.fmu.experiment import Experiment
messages = []
with Experiment(sys.argv[1], fmi_type="CoSimulation") as experiment:   # removes its extracted copy
    fmu = experiment.instantiate(on_message=lambda *m: messages.append(m))
    fmu.setupExperiment(startTime=1e20)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    try:
        fmu.doStep(1e20, 3e6)
    except FMICallException:
        print(messages[-1][2])
    fmu.freeInstance()
"""


@pytest.mark.parametrize("which", ["6", "7"])
def test_cvodes_own_error_message_reaches_the_log_and_not_stderr(fmu7, fmu_path, which):
    # At t = 1e20 a double resolves time only to 1.6e4, far above the contact's time scale: CVODE's
    # error test fails at its smallest step (CV_ERR_FAILURE, -3). (A tolerance below double precision,
    # this test's case before, is now clamped to 1e-12.) SUNDIALS 6 hands the message to CVODE's error
    # handler, 7 to the context's handler stack (whose default prints on stderr): both must end in the
    # fmi2Error log message only.
    r = subprocess.run([sys.executable, "-c", CVODE_FAILURE, fmu7 if which == "7" else fmu_path],
                       capture_output=True, text=True)
    assert r.returncode == 0 and r.stderr == "", r.stderr
    # Nothing else on stdout: SUNDIALS 7's logger, which prints its warning before the failure (that
    # t + h = t) there by default, writes nowhere. (7 names the function cvHandleFailure.)
    printed = r.stdout.strip().splitlines()
    assert len(printed) == 1, r.stdout
    logged = printed[0]
    assert logged.startswith("fmi2DoStep: CVODE failed at t = 1e+20: ")
    assert "(-3): At t = 1e+20" in logged and "the error test failed repeatedly" in logged
