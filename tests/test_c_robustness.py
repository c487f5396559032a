"""The FMU's C code under AddressSanitizer + UBSan, valgrind memcheck and
libFuzzer: tests/c is built with clang (its own CMake project, which compiles
fmu_src itself), the driver exercises every FMI call against the dlopened
library, the fuzz target runs for a bounded time, and any report fails.
cvode_setup_faults fails each SUNDIALS call of Co-Simulation's set-up in turn.

The driver's conformance table (tests/c/conformance_*.c: every FMI 2.0 call in
every state of both interfaces, to the letter of FMI 2.0.4) is its own test,
apart from the robustness checks; valgrind runs both. The FMI 3.0 layer has its
own driver (tests/c/fmi3_*.c: every fmi3 call in every state to the letter of
FMI 3.0, derivatives, robustness) and fuzz target (fuzz_fmi3.c), over the same
instrumented libraries, which export both layers; both fuzz targets replay the
whole corpus.

ROBUSTNESS_FMU_SRC=/path/to/fmu_src points the builds at another copy of the
sources (to check that a planted bug is caught); FUZZ_SECONDS sets the fuzzing
time (default 45), FUZZ3_SECONDS the FMI 3.0 target's (default 20)."""
import os
import pathlib
import re
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
C_TESTS = ROOT / "tests" / "c"
CORPUS = C_TESTS / "corpus"
FUZZ_SECONDS = int(os.environ.get("FUZZ_SECONDS", "45"))
FUZZ3_SECONDS = int(os.environ.get("FUZZ3_SECONDS", "20"))

SANITIZER_ENV = {
    "ASAN_OPTIONS": "detect_leaks=1:halt_on_error=1:detect_stack_use_after_return=1:strict_string_checks=1:"
                    "check_initialization_order=1",
    "UBSAN_OPTIONS": "print_stacktrace=1:halt_on_error=1",
}
REPORT_MARKERS = ("ERROR: AddressSanitizer", "ERROR: LeakSanitizer", "runtime error:", "SUMMARY: AddressSanitizer",
                  "SUMMARY: UndefinedBehaviorSanitizer", "SUMMARY: libFuzzer", "deadly signal", "invariant broken",
                  "FAIL ")


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    """The instrumented libraries, the driver and the fuzz target, built afresh in a
    temporary directory (so that concurrent test runs never share a build tree)."""
    missing = [tool for tool in ("clang", "valgrind", "cmake") if not shutil.which(tool)]
    if missing:
        pytest.fail(f"{' '.join(missing)} not found: `bash run.sh test` installs clang, libclang-rt-14-dev, valgrind")
    out = tmp_path_factory.mktemp("c-robustness")
    fmu_src = pathlib.Path(os.environ.get("ROBUSTNESS_FMU_SRC", ROOT / "fmu_src")).resolve()
    configure = ["cmake", "-S", str(C_TESTS), "-B", str(out), "-DCMAKE_C_COMPILER=clang",
                 f"-DPython3_EXECUTABLE={sys.executable}", f"-DFMU_SRC_DIR={fmu_src}",
                 f"-DMODEL_DESCRIPTION={ROOT / 'modelDescription.xml'}"]
    for cmd in (configure, ["cmake", "--build", str(out), "-j", "2"]):
        r = subprocess.run(cmd, capture_output=True, text=True)
        assert r.returncode == 0, f"{' '.join(cmd)} failed:\n{r.stdout[-4000:]}\n{r.stderr[-4000:]}"
    return out


def run(cmd, timeout, env=None):
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=timeout,
                       env={**os.environ, **SANITIZER_ENV, **(env or {})})
    return r.returncode, r.stdout + r.stderr


def assert_clean(code, output, what):
    reports = [line for line in output.splitlines() if any(m in line for m in REPORT_MARKERS)]
    assert code == 0 and not reports, f"{what} exited {code}:\n" + "\n".join(reports[:40]) + "\n" + output[-6000:]


def test_driver_finds_nothing_under_address_and_undefined_behaviour_sanitizers(build):
    code, output = run([build / "fmi_driver_asan", "--no-conformance", "--cycles", "3000"], timeout=300)
    assert_clean(code, output, "fmi_driver_asan")
    assert " 0 failed" in output


def test_every_fmi2_call_in_every_state_answers_as_fmi_2_0_4_requires(build):
    # The tables of FMI 2.0.4 sections 3.2.3 and 4.2.4, the status queries of 4.2.3,
    # the Error state of 2.1.3 and the directional derivatives of 2.1.9 that
    # modelDescription.xml's ModelStructure defines, under AddressSanitizer + UBSan.
    code, output = run([build / "fmi_driver_asan", "--conformance-only"], timeout=300)
    assert_clean(code, output, "fmi_driver_asan --conformance-only")
    assert " 0 failed" in output


VALGRIND = ["valgrind", "--error-exitcode=99", "--leak-check=full", "--track-origins=yes",
            "--show-leak-kinds=definite,indirect,possible", "--errors-for-leak-kinds=definite,indirect,possible"]


def test_driver_finds_nothing_under_valgrind_memcheck(build):
    code, output = run([*VALGRIND, build / "fmi_driver", "--no-conformance", "--cycles", "300"], timeout=300)
    assert_clean(code, output, "valgrind fmi_driver")
    assert "ERROR SUMMARY: 0 errors" in output, output[-3000:]


def test_a_failed_cvode_set_up_frees_what_it_made_and_the_instance_recovers(build):
    # cvode_setup_faults.c: each SUNDIALS call of Co-Simulation's set-up and restarts fails in turn
    # (fail_sundials_call.c); fmi2Error naming the call, no leak, and after fmi2Reset the same IWC.
    code, output = run(["valgrind", "--error-exitcode=99", "--leak-check=full", "--track-origins=yes",
                        "--show-leak-kinds=definite,indirect,possible",
                        "--errors-for-leak-kinds=definite,indirect,possible",
                        build / "cvode_setup_faults"], timeout=300)
    assert_clean(code, output, "valgrind cvode_setup_faults")
    assert "ERROR SUMMARY: 0 errors" in output, output[-3000:]
    assert re.search(r"CVODE failing at each of its \d+ SUNDIALS calls: \d+ checks, 0 failed", output), output[-3000:]


def test_conformance_calls_find_nothing_under_valgrind_memcheck(build):
    # Memory only: whether each call answers as the standard requires is the test above
    # (a failed check exits 1, valgrind's finding 99).
    code, output = run([*VALGRIND, build / "fmi_driver", "--conformance-only"], timeout=300)
    reports = [line for line in output.splitlines() if any(m in line for m in REPORT_MARKERS[:-1])]
    assert code in (0, 1) and not reports, f"valgrind fmi_driver --conformance-only exited {code}:\n{output[-6000:]}"
    assert "ERROR SUMMARY: 0 errors" in output, output[-3000:]


def test_100000_instantiate_simulate_free_cycles_keep_memory_flat(build):
    # Each cycle allocates two blocks; a leak of even one would grow the resident set by 3 MB.
    code, output = run([build / "fmi_driver", "--no-api", "--cycles", "100000", "--max-rss-growth-kb", "512"],
                       timeout=300)
    assert_clean(code, output, "fmi_driver --cycles 100000")
    assert "100000 instantiate/simulate/free cycles" in output


FUZZ_TARGETS = {"fuzz_fmi": FUZZ_SECONDS, "fuzz_fmi3": FUZZ3_SECONDS}


@pytest.mark.parametrize("target", sorted(FUZZ_TARGETS))
def test_fuzz_seeds_and_regression_inputs_replay_clean(build, target):
    inputs = sorted(CORPUS.iterdir())
    assert inputs, f"{CORPUS} is empty"
    code, output = run([build / target, *inputs], timeout=300)
    assert_clean(code, output, f"{target} on tests/c/corpus")
    assert output.count("Executed ") == len(inputs), output[-3000:]


@pytest.mark.parametrize("target", sorted(FUZZ_TARGETS))
def test_fuzzing_finds_nothing(build, tmp_path, target):
    seconds = FUZZ_TARGETS[target]
    corpus, artifacts = tmp_path / "corpus", tmp_path / "artifacts"
    corpus.mkdir()
    artifacts.mkdir()
    # New inputs go to the temporary corpus, the first directory; tests/c/corpus is only read.
    # The value profile rewards inputs that come closer to a comparison's other side
    # (a length one past a buffer's end is found in seconds rather than minutes).
    code, output = run([build / target, "-seed=1", "-use_value_profile=1", f"-max_total_time={seconds}",
                        "-runs=3000000", "-timeout=10", "-rss_limit_mb=2048", "-print_final_stats=1",
                        f"-artifact_prefix={artifacts}/", corpus, CORPUS], timeout=seconds + 120)
    found = sorted(p.name for p in artifacts.iterdir())
    if found:
        keep = ROOT / "build" / "fuzz-findings"
        keep.mkdir(parents=True, exist_ok=True)
        for name in found:
            shutil.copy(artifacts / name, keep / name)
        output += (f"\nInputs kept in {keep}: {found}. Replay one with `{target} FILE`; once the FMU is fixed, "
                   "add it to tests/c/corpus as a regression case.")
    assert_clean(code, output, target)
    assert not found
    assert "Done " in output


def test_every_fmi3_call_in_every_state_answers_as_fmi_3_0_requires(build):
    # The "Allowed Function Calls" of FMI 3.0 sections 2.3 (common states; an fmi3Error
    # leaves the instance in Terminated), 3.2 (Continuous-Time Mode) and 4.2 (Step Mode),
    # each variable by its getter and setter, and the directional and adjoint derivatives
    # of every (unknown, known) pair of the FMI 3.0 ModelStructure against central
    # differences, under AddressSanitizer + UBSan.
    code, output = run([build / "fmi3_driver_asan", "--conformance-only"], timeout=300)
    assert_clean(code, output, "fmi3_driver_asan --conformance-only")
    assert re.search(r"fmi3_driver: \d+ checks, 0 failed", output), output[-3000:]


def test_fmi3_driver_finds_nothing_under_address_and_undefined_behaviour_sanitizers(build):
    # NULLs, nValues != nValueReferences, every type by every value reference, ranges named
    # in messages, early return and Event Mode (a step with an event pending is refused),
    # serialized states cut short or changed, what the FMU does not have.
    code, output = run([build / "fmi3_driver_asan", "--no-conformance"], timeout=300)
    assert_clean(code, output, "fmi3_driver_asan --no-conformance")
    assert re.search(r"fmi3_driver: \d+ checks, 0 failed", output), output[-3000:]


def test_fmi3_driver_finds_nothing_under_valgrind_memcheck(build):
    code, output = run([*VALGRIND, build / "fmi3_driver"], timeout=300)
    assert_clean(code, output, "valgrind fmi3_driver")
    assert "ERROR SUMMARY: 0 errors" in output, output[-3000:]
    assert re.search(r"fmi3_driver: \d+ checks, 0 failed", output), output[-3000:]


def test_a_state_on_a_stick_fold_leaves_it_by_a_state_the_fold_depends_on(build):
    # With delta = 0 the fold a + q_+ F_N depends on neither v nor w; the move must not use them.
    code, output = run([build / "rod_unit"], timeout=60)
    assert_clean(code, output, "rod_unit")
    assert "all checks passed" in output
