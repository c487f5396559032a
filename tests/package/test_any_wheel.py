# SPDX-License-Identifier: BSD-2-Clause
"""One wheel for every platform: `bash run.sh platforms` makes build/platforms/dist/
painleve-*-py3-none-any.whl, whose painleve package carries the multi-platform FMI 2.0 FMUs
(build/platforms/: linux64, win64 and darwin64 binaries in each). Installed into a fresh
virtual environment (the dependencies pinned by requirements.txt), `painleve iwc` and
`painleve validate` run from it with no build/ directory in sight, on the FMU inside it."""
import json
import math
import pathlib
import re
import subprocess
import venv
import zipfile

import pytest

from conftest import ROOT

DIST = ROOT / "build" / "platforms" / "dist"
WHEELS = sorted(DIST.glob("painleve-*.whl"))


@pytest.fixture(scope="module")
def wheel():
    assert len(WHEELS) == 1, f"{DIST} holds {WHEELS}: `bash run.sh platforms` makes one wheel there"
    return WHEELS[0]


def test_the_wheel_is_for_every_platform_and_carries_the_multi_platform_fmus(wheel):
    assert re.fullmatch(r"painleve-[^-]+-py3-none-any\.whl", wheel.name), wheel.name
    z = zipfile.ZipFile(wheel)
    assert "Root-Is-Purelib: true" in z.read(next(n for n in z.namelist() if n.endswith(".dist-info/WHEEL"))).decode()
    fmus = sorted(n for n in z.namelist() if n.endswith(".fmu"))
    platform_fmus = sorted(p.name for p in (ROOT / "build" / "platforms").glob("*.fmu"))
    assert fmus == [f"painleve/{n}" for n in platform_fmus]
    for name in fmus:
        assert z.read(name) == (ROOT / "build" / "platforms" / pathlib.PurePosixPath(name).name).read_bytes(), name
        folders = {pathlib.PurePosixPath(n).parent.name
                   for n in zipfile.ZipFile(z.open(name)).namelist() if n.startswith("binaries/") and "." in n}
        assert folders == {"linux64", "win64", "darwin64"}, (name, folders)


def test_the_wheel_installs_in_a_fresh_venv_and_runs_iwc_and_validate(wheel, tmp_path):
    env_dir = tmp_path / "venv"
    venv.create(env_dir, with_pip=True)
    python, painleve = env_dir / "bin" / "python", env_dir / "bin" / "painleve"
    done = subprocess.run([python, "-m", "pip", "install", "-q", "--disable-pip-version-check",
                           "-c", ROOT / "requirements.txt", wheel], capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    site = subprocess.run([python, "-c", "import painleve, pathlib; print(pathlib.Path(painleve.__file__).parent)"],
                          capture_output=True, text=True, check=True, cwd=tmp_path).stdout.strip()
    bundled = f"{site}/PainleveRod.fmu"
    env = {"PATH": "/usr/bin:/bin", "HOME": str(tmp_path)}

    out = subprocess.run([painleve, "iwc", "--eps", "1e-4", "--json"], capture_output=True, text=True,
                         cwd=tmp_path, env=env, timeout=300)
    assert out.returncode == 0, out.stderr
    report = json.loads(out.stdout)
    assert report["fmu"] == bundled
    # Theorem 1: IWC, w/v0 within O(eps ln 1/eps) of e (the bound test_pip_install.py uses)
    eps = 1e-4
    assert report["simulated"]["iwc"] and report["predicted"]["theorem"] == 1
    assert abs(report["simulated"]["w"] / report["case"]["v0"] - report["predicted"]["e"]) < 3 * eps * math.log(1 / eps)

    out = subprocess.run([painleve, "validate", "--json"], capture_output=True, text=True, cwd=tmp_path, env=env,
                         timeout=1800)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    report = json.loads(out.stdout)
    assert report["fmu"] == bundled and report["passed"] and report["checks"]
