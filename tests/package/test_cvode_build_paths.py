# SPDX-License-Identifier: BSD-2-Clause
"""One CVODE for every build path (cmake/PainleveCvodeSources.cmake, docs/platforms.md).

The sdist that `python -m build --sdist` makes of the repository holds no SUNDIALS. A wheel built
from it by pip in a fresh virtual environment, with no -DPAINLEVE_CVODE_SOURCE_DIR, downloads the
crate cmake/sundials.pin pins (checked here against the pin with hashes computed here), and its
FMUs carry in sources/ the very files that the FMUs of build/ carry (run.sh builds those from the
tree cargo fetched), the CVODE subset included. The rod's sources from that wheel, built as an
importer builds them with the system's SUNDIALS out of sight, run Co-Simulation as the FMU's own
binary does. A crate fetched by hand gives the same sources with no network; a crate or a tree that
is not the pinned one stops the build; and where the crate cannot be had, the build says so once
and its FMUs carry no sources/, which could not build the Co-Simulation they declare."""
import hashlib
import io
import os
import re
import shutil
import subprocess
import sys
import tarfile
import venv
import zipfile

import fmpy
import numpy as np
import pytest

from conftest import ROOT
from helpers.source_build import assert_cvode_compiled_in, cosimulation_from_sources

BUILD = ROOT / "build"
PIN = dict(re.findall(r"^([A-Z0-9_]+)=(\S+)$", (ROOT / "cmake" / "sundials.pin").read_text(), re.M))
CRATE = f"sundials-sys-{PIN['SUNDIALS_SYS_VERSION']}"
UNREACHABLE = "file:///nonexistent/sundials-sys.crate"   # a download that fails at once, as offline
CVODE_NOTICE = "its CVODE subset in sources/"              # license.txt's line for sources/'s SUNDIALS


def sha256(data):
    return hashlib.sha256(data).hexdigest()


def tree_sha256(root):
    """run.sh's hash of a tree: sha256sum's line ("HASH  ./PATH") of every file, in byte order of
    the paths, hashed together."""
    files = sorted((p for p in root.rglob("*") if p.is_file() and not p.is_symlink()),
                   key=lambda p: os.fsencode(p.relative_to(root).as_posix()))
    return sha256("".join(f"{sha256(p.read_bytes())}  ./{p.relative_to(root).as_posix()}\n" for p in files).encode())


def sundials_version(tree):
    parts = dict(re.findall(r'set\(PACKAGE_VERSION_(MAJOR|MINOR|PATCH) "(\d+)"\)', (tree / "CMakeLists.txt").read_text()))
    return f"{parts['MAJOR']}.{parts['MINOR']}.{parts['PATCH']}"


def clean_env():
    """This environment less anything that could hand the build SUNDIALS sources or CMake options."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PAINLEVE_", "SKBUILD", "CMAKE_"))}
    env["CMAKE_BUILD_PARALLEL_LEVEL"] = "2"
    return env


def cmake(*args):
    """The venv's cmake (requirements.txt) on ARGS, with a clean environment."""
    tool = shutil.which("cmake", path=os.pathsep.join([os.path.dirname(sys.executable), os.environ["PATH"]]))
    return subprocess.run([tool, *map(str, args)], capture_output=True, text=True, env=clean_env(), timeout=900)


def configure(where, *defines):
    return cmake("-S", ROOT, "-B", where, f"-DPython3_EXECUTABLE={sys.executable}", *defines)


def entries(data, prefix):
    """{name: bytes} of the archive DATA's files under PREFIX."""
    z = zipfile.ZipFile(io.BytesIO(data))
    return {n: z.read(n) for n in z.namelist() if n.startswith(prefix) and not n.endswith("/")}


@pytest.fixture(scope="module")
def sdist(tmp_path_factory):
    out = tmp_path_factory.mktemp("sdist")
    done = subprocess.run([sys.executable, "-m", "build", "--sdist", "--no-isolation", "--outdir", str(out), str(ROOT)],
                          capture_output=True, text=True, env=clean_env(), timeout=600)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    made = sorted(out.glob("painleve-*.tar.gz"))
    assert len(made) == 1, made
    return made[0]


@pytest.fixture(scope="module")
def sdist_wheel(sdist, tmp_path_factory):
    """The wheel pip builds from the sdist in a fresh virtual environment (the build's own
    requirements, pinned in pyproject.toml, in pip's isolated environment), and its CMake build tree."""
    where = tmp_path_factory.mktemp("from-sdist")
    venv.create(where / "venv", with_pip=True)
    build_dir = where / "build"
    done = subprocess.run([where / "venv" / "bin" / "python", "-m", "pip", "wheel", "-q", "--disable-pip-version-check",
                           "--no-deps", "-w", where / "dist", "-C", f"build-dir={build_dir}", sdist],
                          capture_output=True, text=True, cwd=where, env=clean_env(), timeout=1800)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    wheels = sorted((where / "dist").glob("painleve-*.whl"))
    assert len(wheels) == 1, wheels
    return wheels[0], build_dir


def test_the_sdist_holds_no_sundials_and_its_wheel_downloaded_the_pinned_crate(sdist, sdist_wheel):
    names = tarfile.open(sdist).getnames()
    assert any(n.endswith("/cmake/sundials.pin") for n in names)
    assert not [n for n in names if n.endswith(("/cvode.c", "/sundials_config.in"))]
    wheel, build_dir = sdist_wheel
    cache = (build_dir / "CMakeCache.txt").read_text()
    assert re.search(r"^PAINLEVE_CVODE_SOURCE_DIR:PATH=$", cache, re.M), "the wheel's build was given a SUNDIALS tree"
    crate = build_dir / "sundials-sources" / f"{CRATE}.crate"
    assert sha256(crate.read_bytes()) == PIN["SUNDIALS_CRATE_SHA256"]
    assert tree_sha256(build_dir / "sundials-sources" / CRATE / "vendor") == PIN["SUNDIALS_TREE_SHA256"]


def test_the_sdist_wheels_fmus_carry_the_same_sources_as_the_plain_builds(sdist_wheel):
    wheel, _ = sdist_wheel
    z = zipfile.ZipFile(wheel)
    fmus = sorted(n for n in z.namelist() if n.endswith(".fmu"))
    assert fmus == sorted(f"painleve/{p.name}" for p in BUILD.glob("*.fmu")), fmus
    for name in fmus:
        data, ours = z.read(name), (BUILD / name.split("/")[-1]).read_bytes()
        sources = entries(data, "sources/")
        assert "sources/sundials_src/cvode.c" in sources and "sources/cvode_bundled.h" in sources, name
        assert sources == entries(ours, "sources/"), f"{name}: sources/ differ from build/'s"
        description = entries(data, "modelDescription.xml")["modelDescription.xml"]
        assert b'<File name="sundials_src/cvode.c"/>' in description and b"<CoSimulation" in description
        assert description == entries(ours, "modelDescription.xml")["modelDescription.xml"], name
        assert CVODE_NOTICE in entries(data, "documentation/licenses/license.txt")[
            "documentation/licenses/license.txt"].decode(), name


def test_the_sdist_wheels_rod_builds_cosimulation_from_its_sources_without_system_sundials(sdist_wheel, tmp_path,
                                                                                            monkeypatch):
    wheel, build_dir = sdist_wheel
    fmu = tmp_path / "PainleveRod.fmu"
    fmu.write_bytes(zipfile.ZipFile(wheel).read("painleve/PainleveRod.fmu"))
    monkeypatch.setenv("CMAKE_BUILD_PARALLEL_LEVEL", "2")
    unzipped, binary = cosimulation_from_sources(fmu, tmp_path)
    assert_cvode_compiled_in(binary, sundials_version(build_dir / "sundials-sources" / CRATE / "vendor"))
    # Every doStep succeeds (fmpy raises otherwise), and the run is the FMU's own binary's (Debian's
    # SUNDIALS 6) to the default experiment's tolerance, relative to each output's scale.
    built = fmpy.simulate_fmu(unzipped, fmi_type="CoSimulation")
    own = fmpy.simulate_fmu(str(fmu), fmi_type="CoSimulation")
    tolerance = float(fmpy.read_model_description(str(fmu)).defaultExperiment.tolerance)
    assert len(built) == len(own) > 10
    for name in own.dtype.names:
        x, y = own[name].astype(float), built[name].astype(float)
        assert np.all(np.isfinite(y)), name
        assert np.abs(x - y).max() <= 100 * tolerance * max(np.abs(x).max(), 1e-300), name


def test_a_crate_fetched_by_hand_gives_the_same_sources_with_no_network(sdist_wheel, tmp_path):
    _, build_dir = sdist_wheel
    crate = build_dir / "sundials-sources" / f"{CRATE}.crate"
    done = configure(tmp_path / "b", f"-DPAINLEVE_SUNDIALS_CRATE={crate}", f"-DPAINLEVE_SUNDIALS_CRATE_URL={UNREACHABLE}")
    assert done.returncode == 0 and "CMake Warning" not in done.stderr, done.stdout[-2000:] + done.stderr[-2000:]
    bundle = tmp_path / "b" / "cvode_bundle"
    ours = entries((BUILD / "PainleveRod.fmu").read_bytes(), "sources/")
    made = {f"sources/{p.relative_to(bundle).as_posix()}": p.read_bytes() for p in bundle.rglob("*") if p.is_file()}
    assert "sources/sundials_src/cvode.c" in made
    assert made == {n: b for n, b in ours.items() if n in made}, "the bundle differs from build/'s FMU's sources/"
    assert sorted(n for n in ours if n.startswith("sources/sundials_src/")) == \
        sorted(n for n in made if n.startswith("sources/sundials_src/"))


def test_a_crate_or_tree_that_is_not_the_pinned_one_stops_the_build(sdist_wheel, tmp_path):
    _, build_dir = sdist_wheel
    crate = tmp_path / f"{CRATE}.crate"
    crate.write_bytes((build_dir / "sundials-sources" / f"{CRATE}.crate").read_bytes() + b"\0")
    done = configure(tmp_path / "b1", f"-DPAINLEVE_SUNDIALS_CRATE={crate}")
    assert done.returncode != 0 and PIN["SUNDIALS_CRATE_SHA256"] in done.stderr, done.stderr[-2000:]
    tree = tmp_path / "vendor"
    shutil.copytree(build_dir / "sundials-sources" / CRATE / "vendor", tree)
    with open(tree / "src" / "cvode" / "cvode.c", "a") as f:
        f.write("/* changed */\n")
    done = configure(tmp_path / "b2", f"-DPAINLEVE_CVODE_SOURCE_DIR={tree}")
    assert done.returncode != 0 and PIN["SUNDIALS_TREE_SHA256"] in done.stderr, done.stderr[-2000:]


def test_where_the_crate_cannot_be_had_the_build_says_so_and_packs_no_sources(tmp_path):
    done = configure(tmp_path / "b", f"-DPAINLEVE_SUNDIALS_CRATE_URL={UNREACHABLE}")
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    warnings = re.findall(r"^CMake Warning.*$", done.stderr, re.M)
    assert len(warnings) == 1 and "carry no sources/" in done.stderr and UNREACHABLE in done.stderr, done.stderr
    built = cmake("--build", tmp_path / "b", "-j", "2")
    assert built.returncode == 0, built.stdout[-2000:] + built.stderr[-2000:]
    fmus = sorted((tmp_path / "b").glob("*.fmu")) + sorted((tmp_path / "b" / "fmi3").glob("*.fmu"))
    assert len(fmus) == len(list(BUILD.glob("*.fmu"))) + len(list((BUILD / "fmi3").glob("*.fmu")))
    for fmu in fmus:
        data = fmu.read_bytes()
        assert not entries(data, "sources/"), f"{fmu}: sources/ without CVODE"
        description = entries(data, "modelDescription.xml")["modelDescription.xml"]
        assert b"<SourceFiles>" not in description and b"<CoSimulation" in description, fmu
        assert CVODE_NOTICE not in entries(data, "documentation/licenses/license.txt")[
            "documentation/licenses/license.txt"].decode(), fmu
        assert fmpy.read_model_description(str(fmu)).coSimulation is not None
    # Their binaries do the Co-Simulation they declare: the rod's runs as build/'s (the same
    # sources, compiler and SUNDIALS) does.
    for rod in ("PainleveRod.fmu", "fmi3/PainleveRod.fmu"):
        a = fmpy.simulate_fmu(str(tmp_path / "b" / rod), fmi_type="CoSimulation")
        b = fmpy.simulate_fmu(str(BUILD / rod), fmi_type="CoSimulation")
        assert len(a) == len(b) > 10
        for name in a.dtype.names:
            x, y = b[name].astype(float), a[name].astype(float)
            assert np.abs(x - y).max() <= 1e-12 * max(np.abs(x).max(), 1e-300), (rod, name)
