# SPDX-License-Identifier: BSD-2-Clause
"""The FMU's C code under AddressSanitizer + UBSan, valgrind memcheck and
libFuzzer: tests/c is built with clang (its own CMake project, which compiles
fmu_src/ itself), the driver exercises every FMI call against the dlopened
library, the fuzz target runs for a bounded time, and any report fails.
cvode_setup_faults fails each SUNDIALS call of Co-Simulation's set-up in turn.

The driver's conformance table (tests/c/conformance_*.c: every FMI 2.0 call in
every state of both interfaces, to the letter of FMI 2.0.4) is its own test,
apart from the robustness checks; valgrind runs both. The FMI 3.0 layer has its
own driver (tests/c/fmi3_*.c: every fmi3 call in every state to the letter of
FMI 3.0, derivatives, robustness; every model) and fuzz target (fuzz_fmi3.c), over the same
instrumented libraries, which export both layers; both fuzz targets replay the
whole corpus. fuzz_bounded (every model; fuzz_bounded3 for FMI 3.0) fuzzes
whole runs instead: tolerance, start time, step sizes, parameters, states and
inputs, Model Exchange and Co-Simulation; every call must return with a legal
status (Discard from a doStep only, the getters answering after it).

Every model gets the FMI 2.0 and 3.0 drivers and conformance tables and the fuzz targets
(fuzz_fmi3 is PainleveRod's only):
PainleveRod (fmu_src/models/PainleveRod, the top-level modelDescription.xml) and
each fmu_src/models/NAME that tests/c/CMakeLists.txt names by add_model_dir_checks
(programs suffixed _NAME, its FMU built from its own modelDescription.xml's
sources, its tables from that XML); a fmu_src/models/NAME that it does not name
fails test_every_model_has_its_conformance_checks.

ROBUSTNESS_FMU_SRC=/path/to/fmu_src points the builds at another copy of the
sources (to check that a planted bug is caught).

The fuzz runs are deterministic, so that a red run means a defect and not a
slow machine: each target replays the whole corpus, then runs a fixed number
of inputs (FUZZ_RUNS) from a fixed seed (FUZZ_SEED), each input under
libFuzzer's -timeout (FUZZ_INPUT_TIMEOUT seconds: an input that takes longer
is a hang, a finding) and -rss_limit_mb. FUZZ_RUNS=N (all targets) or
FUZZ_RUNS_<target>=N change the counts for a longer run; for a campaign by time
budget see bench/fuzz_campaign.sh."""
import os
import pathlib
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest

from conftest import ROOT

C_TESTS = ROOT / "tests" / "c"
MODELS_DIR = ROOT / "fmu_src" / "models"
CORPUS = C_TESTS / "corpus"
FUZZ_SEED = int(os.environ.get("FUZZ_SEED", "1"))
# Seconds one input may take; one past this is a hang. Most inputs take milliseconds under the
# sanitizers; fuzz_bounded's longest legal ones are 8 doSteps that each use much of the FMU's
# budget of work (about a second each here), so the margin is twice that on a loaded machine.
FUZZ_INPUT_TIMEOUT = int(os.environ.get("FUZZ_INPUT_TIMEOUT", "20"))
FUZZ_RSS_LIMIT_MB = 2048

# Each model's suffix of its programs (fmi_driver_asan{suffix}, fmi_driver{suffix}, fuzz_fmi{suffix}).
MODEL_DIRS = re.findall(r"^add_model_dir_checks\((\w+)\)", (C_TESTS / "CMakeLists.txt").read_text(), re.M)
MODELS = {"PainleveRod": "", **{name: f"_{name}" for name in MODEL_DIRS}}


def model_description(model):
    path = ROOT / "modelDescription.xml" if model == "PainleveRod" else MODELS_DIR / model / "modelDescription.xml"
    return ET.parse(path).getroot()

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


def test_every_model_has_its_conformance_checks():
    models = sorted(p.parent.name for p in MODELS_DIR.glob("*/modelDescription.xml"))
    assert models == sorted(MODEL_DIRS), "tests/c/CMakeLists.txt: add_model_dir_checks(NAME) and tests/c/profiles/NAME.h"


@pytest.mark.parametrize("model", MODELS)
def test_driver_finds_nothing_under_address_and_undefined_behaviour_sanitizers(build, model):
    code, output = run([build / f"fmi_driver_asan{MODELS[model]}", "--no-conformance", "--cycles", "3000"],
                       timeout=300)
    assert_clean(code, output, f"fmi_driver_asan{MODELS[model]}")
    assert " 0 failed" in output


@pytest.mark.parametrize("model", MODELS)
def test_every_fmi2_call_in_every_state_answers_as_fmi_2_0_4_requires(build, model):
    # The tables of FMI 2.0.4 sections 3.2.3 and 4.2.4, the status queries of 4.2.3,
    # the Error state of 2.1.3 and the directional derivatives of 2.1.9 that
    # modelDescription.xml's ModelStructure defines, under AddressSanitizer + UBSan;
    # each input of the XML in FMU states and across a Co-Simulation step.
    code, output = run([build / f"fmi_driver_asan{MODELS[model]}", "--conformance-only"], timeout=300)
    assert_clean(code, output, f"fmi_driver_asan{MODELS[model]} --conformance-only")
    assert re.search(r"fmi_driver: \d+ checks, 0 failed", output), output[-3000:]
    variables = model_description(model).find("ModelVariables")
    names = {v.get("name") for v in variables}
    inputs = [v for v in variables if v.get("causality") == "input"]
    assert f"inputs: {len(inputs)} checked" in output
    if {"F_x", "F_y", "tau", "vx_cm", "vy_cm", "phi"} <= names:
        assert "free flight after a jump of F_x, F_y, tau follows Newton's laws" in output


VALGRIND = ["valgrind", "--error-exitcode=99", "--leak-check=full", "--track-origins=yes",
            "--show-leak-kinds=definite,indirect,possible", "--errors-for-leak-kinds=definite,indirect,possible"]


@pytest.mark.parametrize("model", MODELS)
def test_driver_finds_nothing_under_valgrind_memcheck(build, model):
    # The cycles' memory is the soak's below: further models run fewer here (CI time).
    cycles = "300" if model == "PainleveRod" else "100"
    code, output = run([*VALGRIND, build / f"fmi_driver{MODELS[model]}", "--no-conformance", "--cycles", cycles],
                       timeout=300)
    assert_clean(code, output, f"valgrind fmi_driver{MODELS[model]}")
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


@pytest.mark.parametrize("model", MODELS)
def test_conformance_calls_find_nothing_under_valgrind_memcheck(build, model):
    # Memory only: whether each call answers as the standard requires is the test above
    # (a failed check exits 1, valgrind's finding 99).
    code, output = run([*VALGRIND, build / f"fmi_driver{MODELS[model]}", "--conformance-only"], timeout=300)
    reports = [line for line in output.splitlines() if any(m in line for m in REPORT_MARKERS[:-1])]
    assert code in (0, 1) and not reports, f"valgrind fmi_driver --conformance-only exited {code}:\n{output[-6000:]}"
    assert "ERROR SUMMARY: 0 errors" in output, output[-3000:]


# PainleveRod 100000 cycles, each further model 20000 (its runs cross more events).
SOAK_CYCLES = {model: 100000 if model == "PainleveRod" else 20000 for model in MODELS}


@pytest.mark.parametrize("model", MODELS)
def test_instantiate_simulate_free_cycles_keep_memory_flat(build, model):
    # Each cycle allocates two blocks; a leak of even one would grow the resident set by 3 MB
    # over 100000 cycles (0.6 MB over 20000).
    cycles = SOAK_CYCLES[model]
    code, output = run([build / f"fmi_driver{MODELS[model]}", "--no-api", "--cycles", str(cycles),
                        "--max-rss-growth-kb", "512" if cycles == 100000 else "256"], timeout=300)
    assert_clean(code, output, f"fmi_driver{MODELS[model]} --cycles {cycles}")
    assert f"{cycles} instantiate/simulate/free cycles" in output


# Each target's number of inputs in CI, the same on every machine: 15-40 s each on the shared
# 2-core CI machine (measured at a load of 5-7: fuzz_fmi* 250-300 inputs a second once the corpus
# holds the budget-exhausting regressions, fuzz_bounded*, whole runs, 85-190).
FUZZ_RUNS = {"fuzz_fmi": 10000, "fuzz_fmi3": 10000, "fuzz_bounded": 3000, "fuzz_bounded3": 3000,
             **{f"fuzz_fmi{MODELS[name]}": 8000 for name in MODEL_DIRS},
             **{f"fuzz_bounded{MODELS[name]}": 2000 for name in MODEL_DIRS},
             **{f"fuzz_bounded3{MODELS[name]}": 2000 for name in MODEL_DIRS}}


def fuzz_runs(target):
    return int(os.environ.get(f"FUZZ_RUNS_{target}", os.environ.get("FUZZ_RUNS", FUZZ_RUNS[target])))


def test_fuzz_corpus_files_are_what_corpus_inputs_writes():
    # The regress-issue* inputs are written from readable call sequences (tests/c/corpus_inputs.py).
    r = subprocess.run([sys.executable, str(C_TESTS / "corpus_inputs.py"), "--check"], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr


@pytest.mark.parametrize("target", sorted(FUZZ_RUNS))
def test_fuzz_seeds_and_regression_inputs_replay_clean(build, target):
    # Every input of the corpus, each under the input timeout: a regression input that hangs
    # again is a libFuzzer timeout (red) in FUZZ_INPUT_TIMEOUT seconds.
    inputs = sorted(CORPUS.iterdir())
    assert inputs, f"{CORPUS} is empty"
    code, output = run([build / target, f"-timeout={FUZZ_INPUT_TIMEOUT}", f"-rss_limit_mb={FUZZ_RSS_LIMIT_MB}",
                        *inputs], timeout=300)
    assert_clean(code, output, f"{target} on tests/c/corpus")
    assert output.count("Executed ") == len(inputs), output[-3000:]


@pytest.mark.parametrize("target", sorted(FUZZ_RUNS))
def test_fuzzing_finds_nothing(build, tmp_path, target):
    runs = fuzz_runs(target)
    corpus, artifacts = tmp_path / "corpus", tmp_path / "artifacts"
    corpus.mkdir()
    artifacts.mkdir()
    # New inputs go to the temporary corpus, the first directory; tests/c/corpus is only read,
    # and replayed whole before the first new input. A fixed seed and number of runs make the
    # inputs the same on every machine; -timeout makes a hang a finding, not a stuck job.
    # The value profile rewards inputs that come closer to a comparison's other side
    # (a length one past a buffer's end is found in seconds rather than minutes).
    code, output = run([build / target, f"-seed={FUZZ_SEED}", f"-runs={runs}", "-use_value_profile=1",
                        f"-timeout={FUZZ_INPUT_TIMEOUT}", f"-rss_limit_mb={FUZZ_RSS_LIMIT_MB}",
                        "-print_final_stats=1", f"-artifact_prefix={artifacts}/", corpus, CORPUS],
                       timeout=max(600, runs // 50))
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
    assert f"Done {runs} runs" in output, output[-3000:]
    # the whole corpus was read (libFuzzer's INITED line counts what it kept of it)
    assert re.search(r"INFO: seed corpus: files: %d " % len(list(CORPUS.iterdir())), output), output[-3000:]


@pytest.mark.parametrize("model", MODELS)
def test_every_fmi3_call_in_every_state_answers_as_fmi_3_0_requires(build, model):
    # The "Allowed Function Calls" of FMI 3.0 sections 2.3 (common states; an fmi3Error
    # leaves the instance in Terminated), 3.2 (Continuous-Time Mode) and 4.2 (Step Mode),
    # each variable by its getter and setter, and the directional and adjoint derivatives
    # of every (unknown, known) pair of the FMI 3.0 ModelStructure against central
    # differences, under AddressSanitizer + UBSan.
    program = f"fmi3_driver_asan{MODELS[model]}"
    code, output = run([build / program, "--conformance-only"], timeout=300)
    assert_clean(code, output, f"{program} --conformance-only")
    assert re.search(r"fmi3_driver: \d+ checks, 0 failed", output), output[-3000:]


@pytest.mark.parametrize("model", MODELS)
def test_fmi3_driver_finds_nothing_under_address_and_undefined_behaviour_sanitizers(build, model):
    # NULLs, nValues != nValueReferences, every type by every value reference, ranges named
    # in messages, early return and Event Mode (a step with an event pending is refused; the
    # profile's mode switches counted where it has them), serialized states cut short or
    # changed, what the FMU does not have.
    program = f"fmi3_driver_asan{MODELS[model]}"
    code, output = run([build / program, "--no-conformance"], timeout=300)
    assert_clean(code, output, f"{program} --no-conformance")
    assert re.search(r"fmi3_driver: \d+ checks, 0 failed", output), output[-3000:]


@pytest.mark.parametrize("model", MODELS)
def test_fmi3_driver_finds_nothing_under_valgrind_memcheck(build, model):
    program = f"fmi3_driver{MODELS[model]}"
    code, output = run([*VALGRIND, build / program], timeout=600)
    assert_clean(code, output, f"valgrind {program}")
    assert "ERROR SUMMARY: 0 errors" in output, output[-3000:]
    assert re.search(r"fmi3_driver: \d+ checks, 0 failed", output), output[-3000:]


def test_a_state_on_a_stick_fold_leaves_it_by_a_state_the_fold_depends_on(build):
    # With delta = 0 the fold a + q_+ F_N depends on neither v nor w; the move must not use them.
    code, output = run([build / "rod_unit"], timeout=60)
    assert_clean(code, output, "rod_unit")
    assert "all checks passed" in output


def test_the_arm_gap_state_rows_and_height_match_the_tip_written_independently(build):
    code, output = run([build / "arm_unit"], timeout=60)
    assert_clean(code, output, "arm_unit")
    assert "all checks passed" in output
