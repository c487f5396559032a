# SPDX-License-Identifier: BSD-2-Clause
"""Everything the build ships carries its license and the third-party notices: every FMU
(build/, build/fmi3/, build/platforms/ and its fmi3/, and the FMUs inside the wheels) has
documentation/licenses/ with the project's LICENSE, the license of each SUNDIALS it contains
(the one its binaries link, the one its sources/ carry) copied from where that SUNDIALS came
from, and the FMI headers' license as fmpy's headers state it; documentation/index.html links
them all. Each notice is compared here with its origin, read independently of the build."""
import io
import pathlib
import re
import zipfile

import fmpy
import pytest

from conftest import ROOT

BUILD = ROOT / "build"
LICENSE = (ROOT / "LICENSE").read_bytes()
DEBIAN_COPYRIGHT = pathlib.Path("/usr/share/doc/libsundials-dev/copyright")
FMI_HEADERS = pathlib.Path(fmpy.__file__).parent / "c-code"
SUNDIALS_MARKS = {"7": (b"SUNContext_PushErrHandler", b"CVodeSetErrHandlerFn"),
                  "6": (b"CVodeSetErrHandlerFn", b"SUNContext_PushErrHandler")}


def built_fmus():
    return sorted(p for folder in (BUILD, BUILD / "fmi3", BUILD / "platforms", BUILD / "platforms" / "fmi3")
                  for p in folder.glob("*.fmu"))


def wheels():
    return sorted((BUILD / "platforms" / "dist").glob("*.whl"))


def pinned_sundials():
    """The pinned SUNDIALS tree the plain build was configured with: run.sh's (sundials_source), or the
    one CMake downloaded into the build tree when given none (cmake/PainleveCvodeSources.cmake)."""
    cache = (BUILD / "CMakeCache.txt").read_text()
    found = re.search(r"^PAINLEVE_CVODE_SOURCE_DIR:PATH=(.+)$", cache, re.M)
    downloaded = sorted((BUILD / "sundials-sources").glob("sundials-sys-*/vendor"))
    assert (found and found.group(1)) or downloaded, "build/ has no pinned SUNDIALS tree (bash run.sh main)"
    tree = pathlib.Path(found.group(1)) if found and found.group(1) else downloaded[-1]
    parts = dict(re.findall(r'set\(PACKAGE_VERSION_(MAJOR|MINOR|PATCH) "(\d+)"\)', (tree / "CMakeLists.txt").read_text()))
    return tree, f"{parts['MAJOR']}.{parts['MINOR']}.{parts['PATCH']}"


def words(text):
    """Text compared word for word: the FMU's copy may be re-indented, not re-worded."""
    return " ".join(text.replace("*", " ").split())


def fmi_header_licenses():
    """Each FMI header's license: its comment from the copyright line on."""
    out = {}
    for header in sorted(FMI_HEADERS.glob("fmi[23]*.h")):
        text = header.read_text(errors="replace")
        start = text.index("Copyright (C)")
        out[header.name] = words(text[start:text.index("*/", start)])
    return out


def sundials_entries(notice):
    """(file, version, role) of each SUNDIALS line of license.txt."""
    found = re.findall(r"^(SUNDIALS-[^:]+\.txt): SUNDIALS (\S+) CVODE, (statically linked into the binaries|"
                       r"its CVODE subset in sources/)", notice, re.M)
    return [(f, v, "binaries" if r.startswith("statically") else "sources") for f, v, r in found]


def check_fmu(data, name):
    """Every notice of one FMU (its bytes), against its origin."""
    z = zipfile.ZipFile(io.BytesIO(data))
    names = set(z.namelist())
    licenses = sorted(n for n in names if n.startswith("documentation/licenses/") and not n.endswith("/"))
    assert "documentation/licenses/license.txt" in licenses, f"{name}: no documentation/licenses/license.txt"
    assert z.read("documentation/licenses/PainleveRod-LICENSE.txt") == LICENSE, name

    fmi = words(z.read("documentation/licenses/FMI-headers-LICENSE.txt").decode())
    for header, text in fmi_header_licenses().items():
        assert text in fmi, f"{name}: the license of {header} is not in FMI-headers-LICENSE.txt"
    assert f"fmpy {fmpy.__version__}" in fmi

    notice = z.read("documentation/licenses/license.txt").decode()
    entries = sundials_entries(notice)
    binaries = [n for n in names if n.startswith("binaries/") and not n.endswith("/")]
    tree, pinned = pinned_sundials()
    for role in ("binaries", "sources"):
        mine = [(f, v) for f, v, r in entries if r == role]
        carried = binaries if role == "binaries" else [n for n in names if n.startswith("sources/sundials_src/")]
        assert bool(mine) == bool(carried), f"{name}: {role} {carried[:1]} and license.txt's {mine} disagree"
        for file, version in mine:
            text = z.read(f"documentation/licenses/{file}")
            if version == pinned:
                assert text == (tree / "LICENSE").read_bytes(), f"{name}: {file} is not the pinned tree's LICENSE"
            else:
                assert version.startswith("6.") and text == DEBIAN_COPYRIGHT.read_bytes(), \
                    f"{name}: {file} ({version}) is neither the pinned SUNDIALS' nor Debian's"
            if role == "binaries":
                # The major version the notice names is the one inside every binary: its symbol names
                # say which (the error-handler stack of SUNDIALS 7's context, CVODE's own error
                # handler of SUNDIALS 6, removed in 7).
                ours, theirs = SUNDIALS_MARKS[version.split(".")[0]]
                for binary in binaries:
                    data = z.read(binary)
                    assert ours in data and theirs not in data, f"{name}: {binary} is not SUNDIALS {version}"
            else:
                assert text == z.read("sources/sundials_src/LICENSE"), name
                config = z.read("sources/sundials/sundials_config.h").decode()
                assert f'#define SUNDIALS_VERSION "{version}"' in config, name

    index = z.read("documentation/index.html").decode()
    linked = set(re.findall(r'href="(licenses/[^"]+)"', index))
    assert linked == {n[len("documentation/"):] for n in licenses}, f"{name}: index.html links {sorted(linked)}"


FMUS = built_fmus()


def test_the_build_made_fmus_of_every_kind():
    kinds = {p.parent.relative_to(BUILD).as_posix() for p in FMUS}
    assert kinds == {".", "fmi3", "platforms", "platforms/fmi3"}, kinds


@pytest.mark.parametrize("fmu", FMUS, ids=lambda p: p.relative_to(BUILD).as_posix())
def test_every_fmu_carries_its_licenses_and_they_match_their_origins(fmu):
    check_fmu(fmu.read_bytes(), fmu.name)


def test_the_licenses_name_the_sundials_each_build_links():
    """build/ links Debian's SUNDIALS 6.4.1, build/platforms/ the pinned 7.1.1: each says so."""
    tree, pinned = pinned_sundials()
    for fmu, version in ((BUILD / "PainleveRod.fmu", "6.4.1"), (BUILD / "platforms" / "PainleveRod.fmu", pinned)):
        notice = zipfile.ZipFile(fmu).read("documentation/licenses/license.txt").decode()
        assert (f"SUNDIALS-{version}-LICENSE.txt", version, "binaries") in sundials_entries(notice), notice
        assert ("SUNDIALS-7.1.1-LICENSE.txt", "7.1.1", "sources") in sundials_entries(notice), notice


WHEELS = wheels()


def test_run_sh_platforms_made_a_wheel():
    assert WHEELS, f"no wheel in {BUILD / 'platforms' / 'dist'} (bash run.sh platforms)"


@pytest.mark.parametrize("wheel", WHEELS, ids=lambda p: p.name)
def test_the_wheel_carries_the_licenses_and_its_fmus_theirs(wheel):
    z = zipfile.ZipFile(wheel)
    names = z.namelist()
    dist_license = [n for n in names if re.fullmatch(r"painleve-[^/]+\.dist-info/licenses/LICENSE", n)]
    assert dist_license and z.read(dist_license[0]) == LICENSE
    metadata = z.read(next(n for n in names if n.endswith(".dist-info/METADATA"))).decode()
    assert "License-Expression: BSD-2-Clause" in metadata
    assert z.read("painleve/licenses/PainleveRod-LICENSE.txt") == LICENSE
    assert "painleve/licenses/license.txt" in names and "painleve/licenses/FMI-headers-LICENSE.txt" in names
    fmus = [n for n in names if n.endswith(".fmu")]
    assert fmus
    for name in fmus:
        check_fmu(z.read(name), f"{wheel.name}:{name}")


def test_every_source_file_of_the_project_names_its_license():
    """The repository's own sources (C, Python, CMake, shell), tracked by git, each carry the
    SPDX line of LICENSE's BSD-2-Clause in their first lines."""
    import subprocess
    files = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True).stdout.split()
    sources = [f for f in files if re.search(r"\.(c|h|py|cmake|sh)$|(^|/)CMakeLists\.txt$|^\.ci/run$", f)]
    assert len(sources) > 200
    missing = [f for f in sources
               if "SPDX-License-Identifier: BSD-2-Clause" not in "".join((ROOT / f).read_text().splitlines(True)[:3])]
    assert missing == []
    assert b"BSD 2-Clause" in LICENSE or b"Redistribution and use in source and binary forms" in LICENSE
