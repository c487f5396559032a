# SPDX-License-Identifier: BSD-2-Clause
"""A source FMU built as a tool builds it (fmpy's build_platform_binary from <SourceFiles>),
with the SUNDIALS libraries the project's own build found."""
import pathlib
import re
import shutil
import subprocess

import fmpy
from fmpy.build import build_platform_binary

from conftest import ROOT


def sundials_libraries():
    """The static SUNDIALS libraries the project's build found (build/CMakeCache.txt)."""
    cache = (ROOT / "build" / "CMakeCache.txt").read_text()
    libraries = re.findall(r"^SUNDIALS_\w+:FILEPATH=(\S+\.a)$", cache, re.M)
    assert libraries, "the build found no SUNDIALS: `bash run.sh test` installs libsundials-dev"
    return libraries


def with_cvode():
    """The README's defines and libraries for a tool that builds from <SourceFiles> with CVODE."""
    return {"CMAKE_C_FLAGS": "-DHAVE_CVODE", "CMAKE_C_STANDARD_LIBRARIES": " ".join(sundials_libraries() + ["-lm"])}


def source_build(fmu_path, where, cmake_options=None, bundled=True):
    """The FMU's sources extracted into where/fmu, its binaries removed and built anew in where/build.
    bundled=False first takes the CVODE subset out of sources/ and <SourceFiles> (without_bundle):
    the FMU a build without the pinned SUNDIALS sources makes, whose importer links a SUNDIALS."""
    unzipped = fmpy.extract(fmu_path, where / "fmu")
    shutil.rmtree(where / "fmu" / "binaries")
    if not bundled:
        without_bundle(pathlib.Path(unzipped))
    (where / "build").mkdir()
    build_platform_binary(unzipped, build_dir=where / "build", cmake_options=cmake_options)
    return unzipped


def without_bundle(unzipped):
    """An extracted FMU less its CVODE subset (cmake/PainleveCvodeSources.cmake): sources/'s
    SUNDIALS folders, sundials_src/ and cvode_bundled.h, and their files in the model
    description (FMI 2.0 <SourceFiles>, FMI 3.0 buildDescription.xml)."""
    sources = unzipped / "sources"
    for entry in sources.iterdir():
        if entry.name in SUNDIALS_HEADERS or entry.name in ("sundials_src", "cvode_bundled.h"):
            shutil.rmtree(entry) if entry.is_dir() else entry.unlink()
    for xml in (unzipped / "modelDescription.xml", sources / "buildDescription.xml"):
        if xml.exists():
            xml.write_text(re.sub(r'[ \t]*<(?:File|SourceFile) name="sundials_src/[^"]+"\s*/>\n', "", xml.read_text()))


# What Debian's libsundials-dev puts in /usr/include (SUNDIALS 6), and the folders of any other.
SUNDIALS_HEADERS = ("arkode", "cvode", "cvodes", "ida", "idas", "kinsol", "nvector", "sundials", "sunlinsol",
                    "sunmatrix", "sunmemory", "sunnonlinsol", "sunadaptcontroller")


def sysroot_without_sundials(where):
    """A sysroot that is this machine's less every SUNDIALS header, for gcc --sysroot: a source
    build in it cannot reach the system's SUNDIALS, and links only what it names (no -lsundials)."""
    root = where / "sysroot"
    include = root / "usr" / "include"
    include.mkdir(parents=True)
    for entry in pathlib.Path("/usr/include").iterdir():
        if entry.name not in SUNDIALS_HEADERS and not entry.name.startswith("sundials"):
            (include / entry.name).symlink_to(entry)
    for folder in ("lib", "lib64", "usr/lib", "usr/lib64", "usr/local"):
        if pathlib.Path("/", folder).exists():
            (root / folder).parent.mkdir(parents=True, exist_ok=True)
            (root / folder).symlink_to(pathlib.Path("/", folder))
    return root


def without_system_sundials(where):
    """cmake options of a source build whose compiler sees no SUNDIALS of the system's."""
    return {"CMAKE_C_FLAGS": f"--sysroot={sysroot_without_sundials(where)}"}


def cosimulation_from_sources(fmu_path, where):
    """The FMU's sources built as an importer builds them (fmpy's build_platform_binary, with no
    options of ours) by a compiler that sees no SUNDIALS of the system's, in where/: the extracted
    FMU with its new binary, and that binary. The FMU must list the CVODE subset in its sources and
    declare Co-Simulation."""
    unzipped = pathlib.Path(fmpy.extract(str(fmu_path), where / "fmu"))
    md = fmpy.read_model_description(unzipped)
    sources = md.buildConfigurations[0].sourceFileSets[0].sourceFiles
    assert "sundials_src/cvode.c" in sources and md.coSimulation is not None, fmu_path
    shutil.rmtree(unzipped / "binaries")
    (where / "build").mkdir()
    build_platform_binary(unzipped, build_dir=where / "build", cmake_options=without_system_sundials(where))
    return unzipped, next((unzipped / "binaries").glob("*/*.so"))


def assert_cvode_compiled_in(binary, version):
    """CVODE came from sources/: SUNDIALS VERSION is in the binary, and it needs no SUNDIALS library."""
    assert version.encode() in binary.read_bytes(), f"{binary} holds no SUNDIALS {version}"
    needed = subprocess.run(["objdump", "-p", str(binary)], capture_output=True, text=True, check=True).stdout
    assert "sundials" not in needed.lower().split("dynamic section")[1].split("version references")[0]
