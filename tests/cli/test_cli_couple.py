# SPDX-License-Identifier: BSD-2-Clause
"""`painleve couple` run as a user runs it (a subprocess): the coupled study's figure, table and
SSP archive, the printed impulses checked against the written table, every master; bad input
and failed runs end in one line on stderr with nothing left behind in the temporary directory."""
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

from painleve.coupling.ssp import start_values
from painleve.coupling.ssp_check import check_ssp
from conftest import ROOT

ROD = ROOT / "build" / "PainleveRodSI.fmu"
TABLE = ROOT / "build" / "ShakerTable.fmu"


def painleve(*args, tmpdir=None):
    script = pathlib.Path(sys.executable).with_name("painleve")
    cmd = [str(script)] if script.exists() else [sys.executable, "-m", "painleve"]
    env = None if tmpdir is None else dict(os.environ, TMPDIR=str(tmpdir))
    return subprocess.run(cmd + ["couple"] + [str(a) for a in args], capture_output=True, text=True, timeout=300,
                          env=env)


def one_line_error(r, status):
    assert r.returncode == status, f"exit {r.returncode}\nstdout:\n{r.stdout}\nstderr:\n{r.stderr}"
    lines = [line for line in r.stderr.splitlines() if line.strip()]
    assert "Traceback" not in r.stderr and len(lines) == 1, r.stderr
    assert r.stdout == "", r.stdout
    return lines[0]


def test_help_explains_every_option():
    r = painleve("--help")
    assert r.returncode == 0
    for option in ("--rod", "--table", "--master", "--fmi-version", "--coupling", "--stop", "--step", "--set", "--out", "--ssp", "--csv",
                   "--dpi", "fmpy", "libcosim", "ecos", "mean", "instantaneous"):
        assert option in r.stdout, option


@pytest.mark.parametrize("master", ["fmpy", "libcosim", "ecos"])
def test_couple_writes_the_figure_the_table_and_the_archive(master, tmp_path):
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    out = tmp_path / "out"
    r = painleve("--rod", ROD, "--table", TABLE, "--master", master, "--stop", 0.02, "--step", 1e-4,
                 "--set", "table.F0=80", "--out", out / "couple.png", "--csv", out / "couple.csv",
                 "--ssp", out / "coupled.ssp", "--dpi", 40, tmpdir=scratch)
    assert r.returncode == 0, r.stderr
    assert (out / "couple.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert check_ssp(out / "coupled.ssp") == []
    table = np.genfromtxt(out / "couple.csv", delimiter=",", names=True, deletechars="")
    assert len(table) == 200 and table["time"][-1] == pytest.approx(0.02)
    # the printed impulse on the table is the sum of h times the F_N the table held
    line = next(x for x in r.stdout.splitlines() if x.startswith("impulse of F_N"))
    on_table = float(line.split("on the table ")[1].split()[0])
    assert on_table == pytest.approx(1e-4 * np.sum(table["table.F_N"]), rel=1e-5)
    # the table held the rod's step means (the default coupling): the momentum balance closes
    assert "mean coupling" in r.stdout
    np.testing.assert_array_equal(table["table.F_N"][1:], table["rod.F_N_mean"][:-1])
    on_rod = float(line.split("on the rod ")[1].split()[0])
    balance = next(x for x in r.stdout.splitlines() if x.startswith("momentum balance"))
    residual = float(balance.split("residual ")[1].split()[0])
    assert on_rod > 0.1 and abs(residual) <= 1e-6 * on_rod, balance
    # the start value is bound in the archive, beside the defaults of both models
    values = start_values(out / "coupled.ssp")
    assert values["table"]["F0"] == 80 and values["table"]["M"] == 10 and values["rod"]["k"] == 2e7
    assert f"master {master}" in r.stdout
    assert list(scratch.iterdir()) == []                      # nothing left behind


def test_couple_runs_the_fmi3_fmus_in_ecos_as_the_fmi2_ones(tmp_path):
    """--fmi-version 3 takes build/fmi3/*.fmu: the same table as the FMI 2.0 FMUs' to round-off, the
    balance closed, and nothing of ecos's loading chatter on stdout."""
    tables = {}
    for version in ("2", "3"):
        r = painleve("--fmi-version", version, "--master", "ecos", "--stop", 0.02, "--step", 1e-4,
                     "--out", tmp_path / f"{version}.png", "--csv", tmp_path / f"{version}.csv", "--dpi", 40)
        assert r.returncode == 0, r.stderr
        assert f"(FMI {version}.0), master ecos" in r.stdout and "fmi3GetVersion" not in r.stdout + r.stderr
        balance = next(x for x in r.stdout.splitlines() if x.startswith("momentum balance"))
        assert abs(float(balance.split("of the rod's impulse")[0].split("(")[-1])) <= 1e-6, balance
        tables[version] = np.genfromtxt(tmp_path / f"{version}.csv", delimiter=",", names=True, deletechars="")
    assert "build/fmi3/PainleveRodSI.fmu + build/fmi3/ShakerTable.fmu" in r.stdout
    for name in tables["2"].dtype.names:
        np.testing.assert_allclose(tables["3"][name], tables["2"][name], rtol=1e-12, atol=1e-12, err_msg=name)


def test_couple_shows_what_the_instantaneous_coupling_loses(tmp_path):
    """h = 1e-3 against a contact of 0.2 ms: the IWC at t = 0 is over before the first sample of
    F_N, so the table held none of its impulse, and the balance misses all of it."""
    r = painleve("--rod", ROD, "--table", TABLE, "--stop", 0.01, "--step", 1e-3, "--coupling", "instantaneous",
                 "--out", tmp_path / "couple.png", "--dpi", 40)
    assert r.returncode == 0, r.stderr
    line = next(x for x in r.stdout.splitlines() if x.startswith("impulse of F_N"))
    on_rod, on_table = (float(line.split(f"on the {side} ")[1].split()[0]) for side in ("rod", "table"))
    balance = next(x for x in r.stdout.splitlines() if x.startswith("momentum balance"))
    residual = float(balance.split("residual ")[1].split()[0])
    assert on_table == 0 and on_rod > 0.1
    assert residual == pytest.approx(on_rod, rel=1e-3)


@pytest.mark.parametrize("args, expected", [
    (["--rod", "nowhere.fmu"], "--rod nowhere.fmu: no such file"),
    (["--table", ROOT / "build" / "PainleveRod.fmu"], "not the table"),
    (["--rod", TABLE], "not the rod"),
    (["--set", "rod.nope=1"], "--set rod.nope: the rod has no such variable; it takes F_x, F_y, J, c, g, k, l, m, mu, phi, tau, theta, v, w, x, y"),
    (["--set", "rod.F_N=1"], "the rod has no start value to set there"),
    (["--set", "rod.y_floor=1"], "the rod has no start value to set there"),     # the table drives it
    (["--set", "rod.k=-1"], "the SSP is not valid: rod.k = -1.0: outside [1e-06,"),
    (["--set", "k=1"], "is not COMPONENT.NAME=VALUE"),
    (["--stop", 0.1, "--step", 3e-4], "--stop 0.1 is not a whole number of --step 0.0003"),
    (["--step", 0], "argument --step: 0 is not > 0"),
    (["--master", "omsimulator"], "argument --master: invalid choice"),
    (["--fmi-version", 3, "--master", "ecos"], "PainleveRodSI.fmu is an FMI 2.0 FMU; --fmi-version 3 couples FMI 3.0"),
    (["--fmi-version", 3], "--fmi-version 3 --master fmpy: fmpy 0.3.32's simulate_ssp instantiates every FMU"),
    (["--fmi-version", 3, "--master", "libcosim"], "imports FMI 1.0 and 2.0 only"),
])
def test_bad_input_ends_in_one_line(args, expected, tmp_path):
    base = {"--rod": ROD, "--table": TABLE}
    for i in range(0, len(args) - 1, 2):
        base.pop(args[i], None)
    full = [a for kv in base.items() for a in kv] + list(args) + ["--out", tmp_path / "x.png"]
    line = one_line_error(painleve(*full, tmpdir=tmp_path), 2)
    assert expected in line, line
    assert not (tmp_path / "x.png").exists()


@pytest.mark.parametrize("master", ["fmpy", "libcosim"])
def test_a_run_the_fmus_refuse_ends_in_one_line_naming_the_fmus_error(master, tmp_path):
    """A weightless table (1 mg, no spring) driven by 1e9 N runs away: the rod's F_N, fed back to
    the table, leaves the table's input range [-1e9, 1e9] N and the table refuses it."""
    r = painleve("--rod", ROD, "--table", TABLE, "--master", master, "--stop", 0.01,
                 "--set", "table.M=1e-6", "--set", "table.K=0", "--set", "table.C=0", "--set", "table.F0=1e9",
                 "--out", tmp_path / "x.png", tmpdir=tmp_path)
    line = one_line_error(r, 1)
    assert f"the {master} run failed" in line and "is out of range: allowed range is [-1e+09, 1e+09]" in line, line
    assert [p.name for p in tmp_path.iterdir()] == []      # nothing left behind, no figure
