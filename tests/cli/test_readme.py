# SPDX-License-Identifier: BSD-2-Clause
"""The README's code blocks run as written in the set-up `bash run.sh` makes, and print what
their comments say: the Python blocks of the quick start, whose printed values are
checked against the paper's e (computed here by integrating the sticking system) and against
the comments beside them, and the block of `painleve` commands, run verbatim in a fresh
directory that has the build. (The set-up blocks, `bash run.sh ...` and `pip install ...`, are
what CI itself runs and what tests/package/test_pip_install.py runs.)"""
import json
import math
import re
import shlex
import subprocess
import sys

import pandas as pd
import pytest

from painleve.theory import analytic as an
from painleve.experiments.case import Case
from helpers.cli_run import painleve_command
from conftest import ROOT

README = (ROOT / "README.md").read_text()
PYTHON_BLOCKS = re.findall(r"```python\n(.*?)```", README, re.S)
E11 = an.e_integrated(1.0, 1.0)         # e(delta = 1, theta0 = 1), the default case's, by integration


def run_block(code):
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return r.stdout.splitlines()


def commented_values(code):
    """The value each print line's comment says it prints (the text before the first ':')."""
    return [line.split("#", 1)[1].split(":")[0].strip() for line in code.splitlines()
            if line.lstrip().startswith("print(") and "#" in line]


def test_there_are_the_three_quick_start_blocks():
    assert len(PYTHON_BLOCKS) == 3


def test_the_fmpy_quick_start_prints_w_at_lift_off_and_at_the_stop_time():
    code = PYTHON_BLOCKS[0]
    printed = run_block(code)
    assert printed == commented_values(code)                # what the comments say, as printed
    at_lift_off, at_stop = (float(x) for x in printed)
    assert at_lift_off == pytest.approx(E11, rel=2e-3)      # Theorem 1: e v0 to O(eps ln 1/eps), eps = 1e-4
    # free flight (F_N = 0: phi constant, w' = -1 + phi^2 sin theta) from the paper's lift-off state at t ~ 0
    p = an.predict(Case(epsilon=1e-4))
    flight = p.e - 0.1 + p.phi * (math.cos(1.0) - math.cos(1.0 + 0.1 * p.phi))
    assert at_stop == pytest.approx(flight, abs=1e-3)
    assert "fmi_type=" in code                              # says which interface it runs


def test_the_harness_quick_start_prints_w_beside_e():
    code = PYTHON_BLOCKS[1]
    printed = run_block(code)
    assert " ".join(printed) == " ".join(commented_values(code))
    w, e = (float(x) for x in printed[0].split())
    assert e == pytest.approx(round(E11, 5), abs=1e-12) and w == pytest.approx(E11, rel=1e-3)
    assert printed[1] == "True"


def test_the_any_body_quick_start_runs_the_arm_to_its_e():
    """The arm's own start is in the paradox (inconsistent: p_+ < 0, b < 0), so Theorem 1 says w/v0 -> e, with
    e from the FMU's coefficients (eq eGeneral), here through Co-Simulation at eps = 1e-5."""
    code = PYTHON_BLOCKS[2]
    printed = run_block(code)
    assert printed == commented_values(code)
    quadrant, e = printed[0].split()
    assert quadrant == "inconsistent" and float(printed[1]) == pytest.approx(float(e), abs=1e-4)
    assert "CoSimulation" in code and "BodyCase" in code


def command_block():
    """The README's block of `painleve` commands: (command line, comment) pairs."""
    lines = [line.strip() for line in README.splitlines() if line.startswith("    painleve ")]
    return [(line.split("#")[0].strip(), line.split("#")[1].strip() if "#" in line else "") for line in lines]


def test_the_painleve_commands_run_as_written_and_do_what_their_comments_say(tmp_path):
    (tmp_path / "build").symlink_to(ROOT / "build")      # a directory with the build, as after run.sh
    commands = command_block()
    assert [c.split()[1] for c, _ in commands] == ["iwc", "iwc", "validate", "figures", "sweep", "couple"]
    outputs = []
    for command, _ in commands:
        args = shlex.split(command)[1:]
        r = subprocess.run(painleve_command() + args, cwd=tmp_path, capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, (command, r.stderr)
        outputs.append(r.stdout)
    table, theorem2, validation, figures, sweep, couple = outputs
    assert "one case: simulated vs analytic table" == commands[0][1]
    row = next(line for line in table.splitlines() if line.startswith("w at return"))
    simulated, analytic = (float(cell.split()[0]) for cell in re.split(r"\s{2,}", row)[1:3])
    assert analytic == pytest.approx(E11, rel=1e-6) and simulated == pytest.approx(E11, rel=1e-3)
    assert "Theorem 2 (b > 0), JSON for machines" == commands[1][1]
    j = json.loads(theorem2)
    assert j["predicted"]["theorem"] == 2                                     # b > 0: Theorem 2
    assert j["simulated"]["iwc"] == (-0.6 < j["predicted"]["w1_star"])        # IWC below w1*
    assert "all" in validation and "checks passed" in validation
    assert (tmp_path / "out" / "validation.md").exists()
    assert {p.name for p in (tmp_path / "out" / "figures").glob("*.png")} == {"fig_GB.png", "fig_eDelta0.png",
                                                                               "fig_video.png", "fig_eLaw.png",
                                                                               "paradox_region.png"}
    df = pd.read_parquet(tmp_path / "out" / "sweep.parquet")
    assert len(df) == 50 * 2 * 4 * 3 and df["id"].is_unique
    assert (tmp_path / "out" / "couple.png").exists() and "impulse of F_N" in couple


def test_the_readme_is_short_and_every_doc_is_in_the_index():
    """A newcomer's five minutes: the README under about 150 lines; docs/README.md names every page
    of docs/, and every relative link of the README and the index leads to a file."""
    assert len(README.splitlines()) <= 150
    index = (ROOT / "docs" / "README.md").read_text()
    pages = {p.name for p in (ROOT / "docs").glob("*.md")} - {"README.md"}
    assert {p for p in pages if f"]({p})" not in index} == set()
    for text, folder in ((README, ROOT), (index, ROOT / "docs")):
        for link in re.findall(r"\]\(([^)#:]+)\)", text):
            assert (folder / link).exists(), link
