"""A source FMU built as a tool builds it (fmpy's build_platform_binary from <SourceFiles>),
with the SUNDIALS libraries the project's own build found."""
import re
import shutil

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


def source_build(fmu_path, where, cmake_options=None):
    """The FMU's sources extracted into where/fmu, its binaries removed and built anew in where/build."""
    unzipped = fmpy.extract(fmu_path, where / "fmu")
    shutil.rmtree(where / "fmu" / "binaries")
    (where / "build").mkdir()
    build_platform_binary(unzipped, build_dir=where / "build", cmake_options=cmake_options)
    return unzipped
