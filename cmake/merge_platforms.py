# SPDX-License-Identifier: BSD-2-Clause
"""The multi-platform FMUs: every FMU of the first build folder (NAME.fmu, and
fmi3/NAME.fmu: whatever models the build has), with the binaries/ of the FMU at
the same place in each further build folder added, written under OUT.

    python cmake/merge_platforms.py OUT FIRST_BUILD [MORE_BUILDS ...]
"""
import pathlib
import sys
import zipfile


def fmus(build):
    return sorted(p.relative_to(build) for pattern in ("*.fmu", "fmi3/*.fmu") for p in build.glob(pattern))


def binaries(fmu):
    with zipfile.ZipFile(fmu) as z:
        return {n: z.read(n) for n in z.namelist() if n.startswith("binaries/") and not n.endswith("/")}


def merge(out, first, more):
    written = []
    for relative in fmus(first):
        target = out / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        added = {}
        for build in more:
            if not (build / relative).is_file():
                sys.exit(f"{build / relative} is missing: {build} did not build what {first} has")
            added.update(binaries(build / relative))
        with zipfile.ZipFile(first / relative) as z, zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as w:
            for info in z.infolist():
                if info.filename in added:
                    sys.exit(f"{relative}: {info.filename} is in more than one build")
                w.writestr(info, z.read(info.filename))
            for name, data in sorted(added.items()):
                w.writestr(name, data)
        written.append(target)
    return written


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, first, *more = (pathlib.Path(a) for a in sys.argv[1:])
    for path in merge(out, first, more):
        print(path)
