# SPDX-License-Identifier: BSD-2-Clause
"""One pip command installs the harness with its FMU: in a fresh virtual environment,
`pip install` of a copy of the repository (no CMake call by hand) builds PainleveRod.fmu
with the project's CMake (scikit-build-core), puts it inside the painleve package of the
wheel, and `painleve iwc`, run where no build/ directory is, finds and runs it."""
import json
import math
import shutil
import subprocess
import venv

from conftest import ROOT

# What a fresh clone has: the tree without what builds and set-ups leave in it.
LEFT_BY_BUILDS = shutil.ignore_patterns("build", ".venv", ".tools", "out", ".git", "__pycache__", "*.egg-info")


def test_one_pip_install_of_the_repository_gives_a_working_painleve_iwc(tmp_path):
    source = tmp_path / "repo"
    shutil.copytree(ROOT, source, ignore=LEFT_BY_BUILDS, symlinks=True)
    env_dir = tmp_path / "venv"
    venv.create(env_dir, with_pip=True)
    python, painleve = env_dir / "bin" / "python", env_dir / "bin" / "painleve"
    # the pinned versions (the build's own are pinned in pyproject.toml)
    done = subprocess.run([python, "-m", "pip", "install", "-q", "--disable-pip-version-check",
                           "-c", ROOT / "requirements.txt", source], capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]

    # the wheel that was installed carried the FMU, inside the package
    site = subprocess.run([python, "-c", "import painleve, pathlib; print(pathlib.Path(painleve.__file__).parent)"],
                          capture_output=True, text=True, check=True, cwd=tmp_path).stdout.strip()
    record = next((tmp_path / "venv").glob("lib/python*/site-packages/painleve-*.dist-info/RECORD")).read_text()
    assert "painleve/PainleveRod.fmu," in record
    bundled = f"{site}/PainleveRod.fmu"

    out = subprocess.run([painleve, "iwc", "--eps", "1e-4", "--json"], capture_output=True, text=True,
                         cwd=tmp_path, env={"PATH": "/usr/bin:/bin"}, timeout=300)
    assert out.returncode == 0, out.stderr
    report = json.loads(out.stdout)
    assert report["fmu"] == bundled
    simulated, predicted = report["simulated"], report["predicted"]
    # Theorem 1: IWC, w/v0 within O(eps ln 1/eps) of e (the bound test_second_importer.py uses)
    eps = 1e-4
    assert simulated["iwc"] and predicted["theorem"] == 1
    assert abs(simulated["w"] / report["case"]["v0"] - predicted["e"]) < 3 * eps * math.log(1 / eps)

    # the coupled study (painleve couple) runs on the rod in SI units and the table installed with it
    out = subprocess.run([painleve, "couple", "--stop", "0.01", "--out", str(tmp_path / "couple.png")],
                         capture_output=True, text=True, cwd=tmp_path, env={"PATH": "/usr/bin:/bin"}, timeout=300)
    assert out.returncode == 0, out.stderr
    assert f"{site}/PainleveRodSI.fmu + {site}/ShakerTable.fmu" in out.stdout
    assert (tmp_path / "couple.png").read_bytes()[:4] == b"\x89PNG"
