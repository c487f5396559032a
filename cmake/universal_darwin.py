# SPDX-License-Identifier: BSD-2-Clause
"""FMI 2.0's darwin64 folder holds one binary for every Mac: OUT gets each FMU of the
x86_64-darwin build (NAME.fmu, fmi3/NAME.fmu), the FMI 2.0 ones with, in place of their
x86_64 binaries/darwin64/NAME.dylib, the universal binary of that library and the
aarch64-darwin build's NAME.dylib (its FMI 2.0 library, which that build packs nowhere:
FMI 2.0 names no aarch64 folder), made by llvm-lipo. cmake/merge_platforms.py takes OUT as
the build of darwin64 and x86_64-darwin.

    python cmake/universal_darwin.py LIPO OUT X86_64_BUILD AARCH64_BUILD
"""
import shutil
import pathlib
import subprocess
import sys
import tempfile
import zipfile


def universal(lipo, fmu, arm_build, target):
    with zipfile.ZipFile(fmu) as z:
        infos = z.infolist()
        data = {i.filename: z.read(i.filename) for i in infos}
    dylibs = [n for n in data if n.startswith("binaries/darwin64/") and n.endswith(".dylib")]
    if len(dylibs) != 1:
        sys.exit(f"{fmu}: binaries/darwin64/ holds {dylibs}, not one library")
    name = pathlib.PurePosixPath(dylibs[0]).name
    arm = arm_build / name
    if not arm.is_file():
        sys.exit(f"{arm} is missing: the aarch64-darwin build did not build what {fmu} has")
    with tempfile.TemporaryDirectory() as work:
        x86 = pathlib.Path(work) / "x86_64.dylib"
        x86.write_bytes(data[dylibs[0]])
        out = pathlib.Path(work) / name
        subprocess.run([lipo, "-create", str(x86), str(arm), "-output", str(out)], check=True)
        data[dylibs[0]] = out.read_bytes()
    with zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as w:
        for info in infos:
            w.writestr(info, data[info.filename])


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    lipo, (out, x86_build, arm_build) = sys.argv[1], (pathlib.Path(a) for a in sys.argv[2:])
    fmus = sorted(x86_build.glob("*.fmu"))
    if not fmus:
        sys.exit(f"{x86_build} has no FMI 2.0 FMU")
    shutil.rmtree(out, ignore_errors=True)
    (out / "fmi3").mkdir(parents=True)
    for fmu in fmus:
        universal(lipo, fmu, arm_build, out / fmu.name)
    for fmu in sorted(x86_build.glob("fmi3/*.fmu")):
        shutil.copyfile(fmu, out / "fmi3" / fmu.name)


if __name__ == "__main__":
    main()
