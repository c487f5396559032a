# SPDX-License-Identifier: BSD-2-Clause
"""Every failure a user can cause ends in one line on stderr that names the input and what to
do, exit status 2 for bad input and 1 for a failed run, and no traceback: bad
numbers and counts, paths that cannot be written, FMUs that are not this model's or do not
load here, an unreachable dask scheduler, a sweep too large to hold."""
import json
import re
import time
import zipfile
import xml.etree.ElementTree as ET

import pytest

from conftest import leftovers
from painleve.experiments.case import RANGES
from helpers.cli_run import one_line_error, run


def rewrite_fmu(src, dst, edit):
    """A copy of the FMU `src` at `dst` with each member's bytes passed through edit(name, data)."""
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            zout.writestr(item, edit(item.filename, zin.read(item.filename)))
    return str(dst)


def edit_description(edit):
    return lambda name, data: edit(data) if name == "modelDescription.xml" else data


@pytest.fixture(scope="module")
def broken_fmus(fmu_path, fmu3_path, tmp_path_factory):
    """FMUs a user may hand the command by mistake, each made from the built one."""
    d = tmp_path_factory.mktemp("broken")
    guid = edit_description(lambda x: re.sub(rb'guid="[^"]*"', b'guid="{00000000-0000-0000-0000-000000000000}"', x))
    other = edit_description(lambda x: x.replace(b'name="y"', b'name="h"')
                             .replace(b'modelName="PainleveRod"', b'modelName="BouncingBall"'))
    other3 = edit_description(lambda x: x.replace(b'name="y"', b'name="h"')
                              .replace(b'modelName="PainleveRod"', b'modelName="BouncingBall"'))
    fmi1 = edit_description(lambda x: x.replace(b'fmiVersion="2.0"', b'fmiVersion="1.0"'))
    return {
        "guid": rewrite_fmu(fmu_path, d / "guid.fmu", guid),
        "binary": rewrite_fmu(fmu_path, d / "binary.fmu", lambda n, x: b"not a library" if n.endswith(".so") else x),
        "other model": rewrite_fmu(fmu_path, d / "other.fmu", other),
        "other model, FMI 3.0": rewrite_fmu(fmu3_path, d / "other3.fmu", other3),
        "FMI 1.0": rewrite_fmu(fmu_path, d / "fmi1.fmu", fmi1),
    }


def bad_input(*args):
    """The command's one line on stderr, having checked exit status 2 and no traceback."""
    r = run(*args)
    assert r.returncode == 2, (r.returncode, r.stderr)
    return one_line_error(r)


# ------------------------------------------------------------------ numbers and counts
@pytest.mark.parametrize("args, words", [
    (["sweep", "--random", "0"], ["--random", "not >= 1"]),           # ran one case before
    (["sweep", "--batch", "0"], ["--batch", "not >= 1"]),             # ran before
    (["sweep", "--workers", "0"], ["--workers", "not >= 1"]),
    (["sweep", "--random", "-3"], ["--random", "negative"]),
    (["sweep", "--random", "2.5"], ["--random", "whole number"]),
    (["iwc", "--eps", "1.5"], ["eps 1.5", "[1e-8, 1]"]),
    (["iwc", "--eps", "nan"], ["not a finite number"]),
    (["iwc", "--theta0", "inf"], ["not a finite number"]),
    (["iwc", "--alpha", "1e7"], ["alpha 1e7", "[1e-6, 1e6]"]),
    (["iwc", "--mu", "2e6"], ["mu 2e6", "[0, 1e6]"]),
    (["iwc", "--delta", "-1"], ["delta -1", "[0, 1e6]"]),
    (["iwc", "--v0", "abc"], ["'abc' is not a number"]),
    (["sweep", "--eps", "1e-9:1e-3:3"], ["--eps", "[1e-8, 1]"]),
    (["sweep", "--alpha", "0,3"], ["--alpha", "[1e-6, 1e6]"]),
    (["sweep", "--theta0", "0.5:1:0"], ["count n", ">= 1"]),
    (["sweep", "--theta0", "0.5:1:x"], ["count n", "integer"]),
    (["figures", "--dpi", "0"], ["--dpi", "[10, 1200]"]),
    (["figures", "--dpi", "1e6"], ["--dpi", "[10, 1200]"]),          # a 10^7-pixel-wide PNG before
    (["validate", "--sample", "-1"], ["--sample", "negative"]),
    (["sweep", "--scheduler", "not an address"], ["--scheduler", "tcp://host:8786"]),
    (["sweep", "--out", "results.xlsx"], [".csv or .parquet"]),
])
def test_bad_numbers_and_counts_end_in_one_line(fmu_path, args, words):
    if args[0] in ("iwc", "sweep", "figures"):
        args = args + ["--fmu", fmu_path]
    line = bad_input(*args)
    for word in words:
        assert word in line, line


def test_the_cli_ranges_are_the_fmus(fmu_path):
    """One range per parameter: the CLI's (case.RANGES) are the min/max of the FMU's model description."""
    with zipfile.ZipFile(fmu_path) as z:
        root = ET.fromstring(z.read("modelDescription.xml"))
    for name, (lo, hi) in RANGES.items():
        real = root.find(f".//ScalarVariable[@name='{name}']/Real")
        assert (float(real.get("min")), float(real.get("max"))) == (lo, hi), name
    # eps = 1, the FMU's upper end, is accepted by the CLI (it was refused: [1e-8, 1) against [1e-8, 1])
    r = run("iwc", "--fmu", fmu_path, "--eps", "1", "--json")
    assert "is not in" not in r.stderr


def test_a_sweep_too_large_is_refused_before_anything_is_allocated(fmu_path, tmp_path):
    out = tmp_path / "big.parquet"
    start = time.monotonic()
    # 10^5 x 10^5 x 10^5 = 10^15 cases: 8 PB of ids alone (the old code tried to allocate them)
    line = bad_input("sweep", "--fmu", fmu_path, "--theta0", "0.5:1.4:100000", "--phi0", "0.3:0.9:100000",
                     "--w10=-1:0:100000", "--out", out)
    assert time.monotonic() - start < 30
    assert "1,000,000,000,000,000 cases" in line and "more than one sweep holds" in line
    assert not out.exists()
    assert "more than one sweep holds" in bad_input("sweep", "--fmu", fmu_path, "--random", 10**12, "--out", out)


# ------------------------------------------------------------------ paths
@pytest.mark.parametrize("command", ["figures --out {file}/figures", "sweep --out {file}/sweep.csv",
                                     "sweep --out {file}/sweep.parquet", "validate {fmu} --report {file}/v.md"])
def test_an_output_path_that_cannot_be_written_is_named_before_any_run(fmu_path, tmp_path, command):
    a_file = tmp_path / "a_file"
    a_file.write_text("")
    args = command.format(file=a_file, fmu=fmu_path).split()
    if args[0] != "validate":
        args += ["--fmu", fmu_path]
    start = time.monotonic()
    line = bad_input(*args)
    assert f"{a_file} is a file, not a directory" in line and time.monotonic() - start < 30


def test_an_output_file_given_as_a_directory_name_is_named(fmu_path, tmp_path):
    assert "it is a directory; give a file name" in bad_input("validate", fmu_path, "--report", tmp_path)


# ------------------------------------------------------------------ other FMUs
@pytest.mark.parametrize("kind, words", [
    ("guid", ["refused to instantiate", "does not match", "rebuild it"]),
    ("binary", ["binary does not load here", "rebuild it"]),
    ("other model", ["model 'BouncingBall'", "not the Painleve rod", "no variable y"]),
    ("other model, FMI 3.0", ["model 'BouncingBall'", "not the Painleve rod"]),
    ("FMI 1.0", ["FMI 1.0 FMU", "FMI 2.0 and 3.0"]),
])
@pytest.mark.parametrize("command", ["iwc", "figures", "sweep"])
def test_an_fmu_that_is_not_a_working_painleve_rod_is_named(broken_fmus, tmp_path, kind, words, command):
    extra = ["--out", tmp_path / ("out.csv" if command == "sweep" else "figs")] if command != "iwc" else []
    before = leftovers()
    line = bad_input(command, "--fmu", broken_fmus[kind], *extra)
    assert broken_fmus[kind] in line
    for word in words:
        assert word in line, line
    assert leftovers() == before          # the extracted copy is gone too


def test_validate_reports_an_fmu_that_does_not_instantiate_as_a_failed_check(broken_fmus):
    r = run("validate", broken_fmus["guid"], "--interface", "ME", "--json")
    assert r.returncode == 1 and "Traceback" not in r.stderr
    assert "instantiate/ME" in json.loads(r.stdout)["failed"]


@pytest.mark.parametrize("kind", ["other model", "FMI 1.0"])
def test_validate_names_an_fmu_of_another_model(broken_fmus, kind):
    assert broken_fmus[kind] in bad_input("validate", broken_fmus[kind])


def test_the_fmi3_fmu_runs_where_the_fmi2_one_does(fmu3_path):
    r = run("iwc", "--fmu", fmu3_path, "--eps", "1e-4", "--json", check_rc=0)
    assert json.loads(r.stdout)["simulated"]["iwc"]


# ------------------------------------------------------------------ runs
def test_an_unreachable_scheduler_is_one_line_with_status_1(fmu_path, tmp_path):
    r = run("sweep", "--fmu", fmu_path, "--scheduler", "tcp://127.0.0.1:9", "--theta0", "1,1.1",
            "--out", tmp_path / "s.csv")
    assert r.returncode == 1
    line = one_line_error(r)
    assert "cannot reach the dask scheduler tcp://127.0.0.1:9" in line and "leave out --scheduler" in line


# ------------------------------------------------------------------ outside the asymptotic regime
def test_iwc_marks_a_case_outside_the_asymptotic_regime_with_the_reason(fmu_path):
    """The issue's case: eps = 0.1, delta = 50 gave +9732 % against e as if it were a result."""
    out = json.loads(run("iwc", "--fmu", fmu_path, "--eps", 0.1, "--delta", 50, "--json", check_rc=0).stdout)
    assert out["regime"]["inside"] is False
    assert out["regime"]["measure"] == pytest.approx(0.1 * 51 ** 3)
    assert "eps (1 + delta)^3" in out["regime"]["reason"]
    table = run("iwc", "--fmu", fmu_path, "--eps", 0.1, "--delta", 50, check_rc=0).stdout
    assert "asymptotic regime: OUTSIDE (eps (1 + delta)^3 = 1.33e+04 > 0.02" in table
    inside = json.loads(run("iwc", "--fmu", fmu_path, "--eps", 1e-4, "--delta", 1, "--json", check_rc=0).stdout)
    assert inside["regime"]["inside"] is True and inside["regime"]["measure"] == pytest.approx(8e-4)
    assert "eps (1 + delta)^3 > 2e-2" in run("iwc", "--help", check_rc=0).stdout.replace("\n", " ").replace(
        "  ", " ")


def test_ctrl_c_during_a_validation_is_one_line_with_status_130_and_leaves_nothing(fmu_path, tmp_path):
    import os
    import signal
    import subprocess
    from helpers.cli_run import painleve_command
    before = leftovers()
    # A sample large enough that the validation (well under a second by default) is still running.
    p = subprocess.Popen(painleve_command() + ["validate", fmu_path, "--sample", "2000", "--report", str(tmp_path / "v.md")],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and not set(leftovers()) - set(before):   # its Experiment is running
        time.sleep(0.02)
    os.killpg(p.pid, signal.SIGINT)
    _, stderr = p.communicate(timeout=60)
    assert p.returncode == 130
    lines = [line for line in stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and "interrupted" in lines[0] and "Traceback" not in stderr, stderr
    assert leftovers() == before and not (tmp_path / "v.md").exists()
