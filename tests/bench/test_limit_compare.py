# SPDX-License-Identifier: BSD-2-Clause
"""bench/limit_compare.py, on one round and one eps: its table has one row per eps with the
columns it promises, and the two sides it times compute the same physics. The FMU's
Co-Simulation (at the tolerance the script picks) and the single-purpose limit.c (at rtol
1e-8) each put every case's w at the return within 1e-6 relative of an independent tight
reference (scipy's DOP853 at rtol 1e-12, the same model in Python), so they agree with each
other within 2e-6 relative; the script's own check is that they agree within 1e-6 relative
of each other too, which the measured errors (below 5e-7 and 1.1e-7) leave room for."""
import subprocess
import sys

import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT / "bench"))
import limit_compare  # noqa: E402

EPS = 1e-3


def test_without_limit_c_it_says_so_in_one_line_and_exits_0(tmp_path):
    missing = tmp_path / "limit.c"
    done = subprocess.run([sys.executable, str(ROOT / "bench" / "limit_compare.py"), "--limit", str(missing)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0
    assert done.stdout.strip().count("\n") == 0 and str(missing) in done.stdout and "not there" in done.stdout


@pytest.fixture(scope="module")
def compared(tmp_path_factory, fmu_path):
    if not limit_compare.LIMIT_C.is_file():
        pytest.skip(f"{limit_compare.LIMIT_C} (the measuring instrument, outside the repository) is not there")
    from fmpy import extract
    tmp = tmp_path_factory.mktemp("limit")
    exe = limit_compare.build_limit(limit_compare.LIMIT_C, tmp)
    fmu_dir = extract(str(fmu_path), str(tmp / "fmu"))
    return limit_compare.compare(exe, fmu_dir, epsilons=(EPS,), rounds=1, repeat=3)


def test_the_table_has_a_row_per_eps_with_its_columns(compared):
    table, before, after = compared
    lines = limit_compare.markdown(table, before, after, 1)
    assert lines[0].startswith("load average") and len(before) == len(after) == 3
    header = [c.strip() for c in lines[2].strip("|").split("|")]
    assert header[:5] == ["eps", "FMU rtol", "FMU us/case (slowest)", "limit.c us/case (slowest)", "ratio"]
    rows = [line for line in lines[4:] if line.startswith("|")]
    assert len(rows) == 1
    cells = [c.strip() for c in rows[0].strip("|").split("|")]
    assert len(cells) == len(header) and float(cells[0]) == EPS
    row = table[0]
    assert row["rtol"] in limit_compare.LADDER
    assert row["fmu_us"] > 0 and row["limit_us"] > 0
    assert row["ratio"] == pytest.approx(row["fmu_us"] / row["limit_us"])


def test_both_sides_land_on_the_reference_and_on_each_other(compared):
    row = compared[0][0]
    assert len(row["w_ref"]) == len(row["w_fmu"]) == len(row["w_limit"]) == 5
    for w_ref, w_fmu, w_limit in zip(row["w_ref"], row["w_fmu"], row["w_limit"]):
        assert abs(w_fmu - w_ref) <= 1e-6 * abs(w_ref)
        assert abs(w_limit - w_ref) <= 1e-6 * abs(w_ref)
        assert abs(w_fmu - w_limit) <= 1e-6 * abs(w_limit)
