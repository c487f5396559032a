# SPDX-License-Identifier: BSD-2-Clause
"""PainleveRod's model_calculated_partial over every pair of value references (and a few past the
list): tests/c/model_partial_refusals.c, compiled here from the model's sources with the FMU's
warnings as errors and under AddressSanitizer + UBSan. A pair the rod's partials do not know is
refused, where it once fell back to another variable's column."""
import shutil
import subprocess

import pytest

from conftest import ROOT

SRC = ROOT / "fmu_src"
FOLDERS = [SRC / "models" / "PainleveRod", SRC / "models", SRC / "rod", SRC / "contact", SRC / "common"]
SOURCES = [SRC / "models" / "PainleveRod" / "model.c", SRC / "models" / "model_common.c", SRC / "rod" / "rod.c",
           SRC / "rod" / "rod_partials.c", SRC / "contact" / "contact.c", SRC / "contact" / "contact_events.c",
           SRC / "contact" / "contact_record.c", ROOT / "tests" / "c" / "model_partial_refusals.c"]
WARNINGS = ["-Wall", "-Wextra", "-Wpedantic", "-Wshadow", "-Wconversion", "-Wno-sign-conversion", "-Werror"]
SANITIZE = ["-fsanitize=address,undefined", "-fno-sanitize-recover=all"]


def test_every_known_pair_is_answered_and_every_other_refused(tmp_path):
    cc = shutil.which("cc")
    if cc is None:
        pytest.fail("no C compiler `cc` on PATH: `bash run.sh test` builds the FMU with it")
    exe = tmp_path / "model_partial_refusals"
    build = [cc, "-std=c99", "-O1", "-g", *WARNINGS, *SANITIZE, *(f"-I{f}" for f in FOLDERS), *map(str, SOURCES),
             "-lm", "-o", str(exe)]
    r = subprocess.run(build, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    r = subprocess.run([str(exe)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "runtime error" not in r.stderr, r.stdout[-6000:] + r.stderr[-6000:]
    answered, refused = (int(r.stdout.split()[i]) for i in (0, 3))
    assert answered > 0 and refused > 0 and r.stdout.rstrip().endswith("0 failed"), r.stdout
