# SPDX-License-Identifier: BSD-2-Clause
"""The `painleve sweep` command run as a user runs it (a subprocess), with what it wrote
checked: dask equals serial; an interrupted sweep (on dask or in this process) resumes without recomputing; a row cut
by a crash is rerun; a different sweep into the same file is refused."""
import os
import signal
import subprocess
import time

import numpy as np
import pandas as pd
import pytest

from painleve.theory import analytic as an
from painleve.sweep.store import ResultStore
from helpers.cli_run import one_line_error, painleve_command, run


# ------------------------------------------------------------------ sweep
SWEEP = ["--theta0", "0.3:1.5:7", "--phi0", "0.5,1.3", "--eps", "1e-5:1e-3:3:log", "--delta", "0,1"]


def test_a_sweep_on_two_dask_workers_gives_the_numbers_of_the_serial_sweep(fmu_path, tmp_path):
    serial, parallel = tmp_path / "serial.csv", tmp_path / "dask.parquet"
    r = run("sweep", "--fmu", fmu_path, *SWEEP, "--serial", "--out", serial, check_rc=0)
    assert "84 of 84 cases" in r.stdout
    r = run("sweep", "--fmu", fmu_path, *SWEEP, "--workers", 2, "--batch", 20, "--out", parallel, check_rc=0)
    assert "local cluster with 2 worker(s)" in r.stderr and "case/s" in r.stderr    # the progress bar
    a, b = ResultStore(serial).read(), ResultStore(parallel).read()
    assert list(a["id"]) == list(range(84))
    pd.testing.assert_frame_equal(a, b, check_exact=True)
    ok = a[a["status"] == "ok"]
    assert len(ok) > 20 and set(a["status"]) == {"ok", "outside"}    # theta0 = 0.3, 1.5 lie outside the wedge
    for _, row in ok.iterrows():    # the predictions, independently of the harness's closed form
        assert row["e"] == pytest.approx(an.e_integrated(row["delta"], row["theta0"]), rel=1e-7)
    fine = ok[(ok["theorem"] == 1) & (ok["epsilon"] == 1e-5)]
    assert len(fine) > 5 and np.all(np.abs(fine["w_error"] / fine["e"]) < 0.01)


def test_an_interrupted_sweep_resumes_without_recomputing_finished_cases(fmu_path, tmp_path):
    """SIGINT to the whole process group (Ctrl-C in a terminal) in the middle of a dask sweep: one
    line saying how many cases are saved and how to resume, none of distributed's ERROR lines; the
    same command then finishes the sweep, each case once."""
    out = tmp_path / "sweep.csv"
    interrupted_and_resumed(out, ["sweep", "--fmu", fmu_path, "--theta0", "0.5:1.4:50", "--phi0", "0.3,0.6", "--eps",
                                  "1e-4,1e-5", "--batch", 10, "--workers", 2, "--out", out, "--no-progress"], 200)


def test_a_sweep_interrupted_in_this_process_resumes_the_same_way(fmu_path, tmp_path):
    """A sweep in this process (the path a short sweep takes; which sweeps take it is
    sweep.plan's, tested with the load pinned in test_sweep_paths.py): Ctrl-C stops it between or
    inside cases alike."""
    out = tmp_path / "sweep.csv"
    stderr = interrupted_and_resumed(out, ["sweep", "--fmu", fmu_path, "--theta0", "0.5:1.4:250", "--phi0", "0.3,0.6",
                                           "--eps", "1e-4,1e-5", "--batch", 10, "--serial", "--out", out,
                                           "--no-progress"], 1000)
    assert "dask" not in stderr


def interrupted_and_resumed(out, args, total):
    p = subprocess.Popen(painleve_command() + [str(a) for a in args], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, start_new_session=True)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and p.poll() is None:
        if out.exists() and out.read_text().count("\n") > 30:
            break
        time.sleep(0.05)
    os.killpg(p.pid, signal.SIGINT)          # Ctrl-C in a terminal: the whole process group
    stdout, stderr = p.communicate(timeout=60)
    assert p.returncode == 130, stdout + stderr
    assert "Traceback" not in stderr and "ERROR" not in stderr and "distributed" not in stderr, stderr
    errors = [line for line in stderr.splitlines() if line.startswith("error:")]
    assert len(errors) == 1 and "run the same command to resume" in errors[0], stderr
    before = out.read_text()
    done = before.count("\n") - 1
    assert 30 <= done < total
    assert f"interrupted; {done} of {total} cases are saved in {out}" in errors[0]
    r = run(*args, check_rc=0)
    assert f"resuming {out}: {done} of {total} cases already done, {total - done} to run" in r.stderr
    after = out.read_text()
    assert after.startswith(before)          # finished rows untouched, the rest appended
    ids = pd.read_csv(out)["id"]
    assert sorted(ids) == list(range(total))  # each case once: none recomputed, none lost, no duplicate
    return stderr


def test_a_csv_row_cut_by_a_crash_is_dropped_and_rerun(fmu_path, tmp_path):
    out = tmp_path / "sweep.csv"
    args = ["sweep", "--fmu", fmu_path, "--theta0", "0.6:1.2:8", "--serial", "--batch", 4, "--out", out]
    run(*args, check_rc=0)
    whole = out.read_text()
    out.write_text(whole[:-25])              # the last row cut in the middle
    r = run(*args, check_rc=0)
    assert "7 of 8 cases already done" in r.stderr
    assert out.read_text() == whole


def test_a_different_sweep_into_the_same_file_is_refused(fmu_path, tmp_path):
    out = tmp_path / "sweep.csv"
    run("sweep", "--fmu", fmu_path, "--theta0", "0.6:1.2:4", "--serial", "--out", out, check_rc=0)
    r = run("sweep", "--fmu", fmu_path, "--theta0", "0.6:1.2:5", "--serial", "--out", out)
    assert r.returncode == 2 and "holds another sweep" in one_line_error(r)
