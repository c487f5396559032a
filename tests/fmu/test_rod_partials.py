# SPDX-License-Identifier: BSD-2-Clause
"""rod_partials (fmu_src/rod/rod_partials.c) against central finite differences of the
functions it differentiates, at random points in every mode: tests/c/rod_partials_check.c,
compiled here with the FMU's warnings as errors and under AddressSanitizer + UBSan."""
import os
import shutil
import subprocess

import pytest

from conftest import ROOT

ROD = ROOT / "fmu_src" / "rod"
CONTACT = ROOT / "fmu_src" / "contact"  # the contact core the rod runs on
COMMON = ROOT / "fmu_src" / "common"  # namespace.h
WARNINGS = ["-Wall", "-Wextra", "-Wpedantic", "-Wshadow", "-Wconversion", "-Wno-sign-conversion", "-Werror"]
SANITIZE = ["-fsanitize=address,undefined", "-fno-sanitize-recover=all"]


def test_rod_partials_match_central_differences_in_every_mode(tmp_path):
    cc = shutil.which("cc")
    if cc is None:
        pytest.fail("no C compiler `cc` on PATH: `bash run.sh test` builds the FMU with it")
    exe = tmp_path / "rod_partials_check"
    build = [cc, "-std=c99", "-O1", "-g", *WARNINGS, *SANITIZE, f"-I{ROD}", f"-I{CONTACT}", f"-I{COMMON}", str(ROD / "rod.c"),
             str(CONTACT / "contact.c"), str(CONTACT / "contact_events.c"), str(ROD / "rod_partials.c"), str(ROOT / "tests" / "c" / "rod_partials_check.c"), "-lm", "-o", str(exe)]
    r = subprocess.run(build, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    r = subprocess.run([str(exe)], capture_output=True, text=True, timeout=120,
                       env={**os.environ, "ASAN_OPTIONS": "detect_leaks=1:halt_on_error=1"})
    assert r.returncode == 0 and "runtime error" not in r.stderr, r.stdout[-6000:] + r.stderr[-6000:]
    assert "at 400 points in each of 5 modes, 0 failed" in r.stdout, r.stdout
