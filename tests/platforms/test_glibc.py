# SPDX-License-Identifier: BSD-2-Clause
"""Which glibc the Linux binaries need. pow, exp and log are linked to glibc's oldest
symbols (cmake/glibc_math.c), not their GLIBC_2.29 ones, so the x86_64 binaries need glibc 2.14
(memcpy) and the aarch64 ones 2.17 (the first aarch64 glibc): RHEL 7 and 8 load them. Read
from each binary's dynamic symbol versions (objdump -T), for the native build and every
multi-platform FMU (build/platforms/, `bash run.sh platforms`)."""
import pathlib
import re
import subprocess
import zipfile

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
NEEDED = {"x86_64": (2, 14), "aarch64": (2, 17)}
OBJDUMP = {"x86_64": "objdump", "aarch64": "aarch64-linux-gnu-objdump"}


def glibc_versions(library, arch):
    dump = subprocess.run([OBJDUMP[arch], "-T", str(library)], capture_output=True, text=True, check=True).stdout
    return {tuple(map(int, v.split("."))) for v in re.findall(r"\(GLIBC_([0-9.]+)\)", dump)}


def native_libraries():
    return sorted((ROOT / "build").glob("*.so")) + sorted((ROOT / "build" / "fmi3" / "lib").glob("*.so"))


@pytest.mark.parametrize("library", native_libraries(), ids=lambda p: p.name)
def test_native_build_needs_glibc_2_14(library):
    versions = glibc_versions(library, "x86_64")
    assert versions and max(versions) <= NEEDED["x86_64"], sorted(versions)[-3:]


def platform_libraries():
    fmus = sorted((ROOT / "build" / "platforms").glob("**/*.fmu"))
    assert fmus, "no build/platforms/ (bash run.sh platforms)"
    return [(fmu, name) for fmu in fmus for name in zipfile.ZipFile(fmu).namelist() if name.endswith(".so")]


def test_every_linux_binary_of_every_platform_fmu_needs_at_most_its_oldest_glibc(tmp_path):
    checked = {}
    for fmu, name in platform_libraries():
        arch = "aarch64" if "/aarch64-" in name else "x86_64"
        library = tmp_path / f"{fmu.stem}-{arch}-{pathlib.PurePosixPath(name).name}"
        library.write_bytes(zipfile.ZipFile(fmu).read(name))
        versions = glibc_versions(library, arch)
        assert versions and max(versions) <= NEEDED[arch], (fmu.name, name, sorted(versions)[-3:])
        checked[arch] = checked.get(arch, 0) + 1
    assert set(checked) == {"x86_64", "aarch64"}, checked
