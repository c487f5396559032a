# SPDX-License-Identifier: BSD-2-Clause
"""The macOS binaries of the multi-platform FMUs (build/platforms/, `bash run.sh platforms`:
zig's clang and Mach-O linker, llvm-lipo-14), checked statically: no Mac runs them here.
FMI 2.0's darwin64 holds one universal library (x86_64 and arm64), FMI 3.0's x86_64-darwin and
aarch64-darwin one library each. Every slice is a 64-bit Mach-O dylib of its CPU for macOS at
the minimum version docs/platforms.md states, loads libSystem alone, is named @rpath/NAME.dylib,
exports the FMI functions the Linux binary of the same FMU exports and nothing else of its own,
and carries CVODE of the pinned SUNDIALS statically; every arm64 slice carries an ad-hoc code
signature whose page hashes match its bytes (macOS loads no unsigned arm64 code). The Mach-O
reading is tests/helpers/macho.py's; the export table is llvm-objdump-14's."""
import pathlib
import re
import subprocess
import sys
import zipfile

import pytest

from helpers import macho

ROOT = pathlib.Path(__file__).resolve().parents[2]
PLATFORMS = ROOT / "build" / "platforms"
FMUS = sorted(str(p.relative_to(PLATFORMS)) for pattern in ("*.fmu", "fmi3/*.fmu") for p in PLATFORMS.glob(pattern))
# What each FMI version's folders must hold: folder -> the slices' architectures.
FOLDERS = {2: {"darwin64": {"x86_64", "arm64"}},
           3: {"x86_64-darwin": {"x86_64"}, "aarch64-darwin": {"arm64"}}}
# The two symbols Mach-O's linker defines in every dylib (the image's header and the DSO handle).
LINKER_SYMBOLS = {"__mh_dylib_header", "___dso_handle"}
CS_ADHOC, CS_LINKER_SIGNED = 0x2, 0x20000


def stated_minimum():
    """The minimum macOS version docs/platforms.md states ("macOS 11.0 or later")."""
    found = re.findall(r"macOS (\d+)\.(\d+) or later", (ROOT / "docs" / "platforms.md").read_text())
    assert len(set(found)) == 1, found
    return tuple(map(int, found[0])) + (0,)


def exports(path, arch):
    dump = subprocess.run(["llvm-objdump-14", "--macho", "--exports-trie", f"--arch={arch}", str(path)],
                          capture_output=True, text=True, check=True).stdout
    return {line.split()[1] for line in dump.splitlines() if re.match(r"0x[0-9A-Fa-f]+ ", line)}


def linux_exports(fmu, folder, tmp_path):
    """The FMI functions the same FMU's x86_64 Linux library exports (objdump -T)."""
    with zipfile.ZipFile(fmu) as z:
        name = next(n for n in z.namelist() if n.startswith(f"binaries/{folder}/") and n.endswith(".so"))
        library = tmp_path / "linux.so"
        library.write_bytes(z.read(name))
    dump = subprocess.run(["objdump", "-T", str(library)], capture_output=True, text=True, check=True).stdout
    return {"_" + line.split()[-1] for line in dump.splitlines() if " g " in line and "DF" in line
            and "*UND*" not in line}


def pinned_sundials_major():
    config = ROOT / "build-platforms" / "x86_64-linux" / "cvode_bundle" / "sundials" / "sundials_config.h"
    return re.search(r"#define SUNDIALS_VERSION_MAJOR (\d+)", config.read_text()).group(1)


def test_every_model_has_its_macos_fmus():
    assert FMUS and {f.startswith("fmi3/") for f in FMUS} == {True, False}, FMUS


@pytest.mark.parametrize("fmu", FMUS)
def test_macos_binaries_pass_the_static_checks(fmu, tmp_path):
    path = PLATFORMS / fmu
    version = 3 if fmu.startswith("fmi3/") else 2
    identifier = pathlib.PurePosixPath(fmu).stem
    minimum = stated_minimum()
    fmi_exports = linux_exports(path, "x86_64-linux" if version == 3 else "linux64", tmp_path)
    assert fmi_exports and all(s.startswith(f"_fmi{version}") for s in fmi_exports), fmi_exports
    with zipfile.ZipFile(path) as z:
        dylibs = {pathlib.PurePosixPath(n).parent.name: n for n in z.namelist() if n.endswith(".dylib")}
        assert set(dylibs) == set(FOLDERS[version]), dylibs
        for folder, name in dylibs.items():
            assert pathlib.PurePosixPath(name).name == f"{identifier}.dylib"
            data = z.read(name)
            library = tmp_path / f"{folder}.dylib"
            library.write_bytes(data)
            # universal (fat) exactly where FMI 2.0 wants one binary for both CPUs
            assert (struct_magic(data) == macho.FAT_MAGIC) == (version == 2), folder
            slices = macho.slices(data)
            assert {arch for arch, _ in slices} == FOLDERS[version][folder] and len(slices) == len(FOLDERS[version][folder])
            for arch, body in slices:
                s = macho.parse(body)
                where = f"{folder} {arch}"
                assert s.arch == arch and s.filetype == macho.MH_DYLIB, where
                assert s.dylibs == ["/usr/lib/libSystem.B.dylib"], (where, s.dylibs)
                assert s.install_name == f"@rpath/{identifier}.dylib", (where, s.install_name)
                assert s.platform == macho.PLATFORM_MACOS and s.minos == minimum, (where, s.platform, s.minos)
                exported = exports(library, arch)
                assert exported - LINKER_SYMBOLS == fmi_exports, (where, sorted(exported ^ fmi_exports))
                # CVODE is inside (static), and it is the pinned SUNDIALS' major version
                if pinned_sundials_major() == "7":
                    assert b"SUNContext_PushErrHandler" in body and b"CVodeSetErrHandlerFn" not in body, where
                if arch == "arm64":
                    sig = s.signature
                    assert sig and sig["magic"] == macho.CSMAGIC_EMBEDDED_SIGNATURE, (where, sig)
                    assert sig["flags"] & CS_ADHOC and sig["pages_ok"], (where, sig)
                    # the signature covers the whole slice up to itself
                    assert sig["code_limit"] == sig["covers_offset"], (where, sig)


def struct_magic(data):
    return int.from_bytes(data[:4], "big")


def fmi_functions(version):
    """Every function the FMI headers of fmpy declare for that version (fmiNFunctions.h's
    FMI_FUNCTION_PREFIX names), with Mach-O's leading underscore."""
    import fmpy
    header = (pathlib.Path(fmpy.__file__).parent / "c-code" / f"fmi{version}Functions.h").read_text()
    return {f"_{name}" for name in re.findall(rf"#define (fmi{version}[A-Z]\w*)\s+fmi{version}FullName", header)}


@pytest.mark.parametrize("fmu", ["PainleveRod.fmu", "fmi3/PainleveRod.fmu"])
def test_the_source_fmu_builds_cosimulation_for_a_mac_with_no_sundials(fmu, tmp_path):
    """sources/ as a Mac's compiler sees them: zig's clang for arm64 macOS, whose include path
    has no SUNDIALS but sources/ (the CVODE subset), the importer's one include folder, and the
    FMI headers. The library links with libSystem alone and exports every FMI function."""
    path = PLATFORMS / fmu
    version = 3 if fmu.startswith("fmi3/") else 2
    with zipfile.ZipFile(path) as z:
        z.extractall(tmp_path / "fmu")
    sources = tmp_path / "fmu" / "sources"
    if version == 3:
        listed = re.findall(r'<SourceFile name="([^"]+)"', (sources / "buildDescription.xml").read_text())
    else:
        listed = re.findall(r'<File name="([^"]+)"', (tmp_path / "fmu" / "modelDescription.xml").read_text())
        listed = list(dict.fromkeys(listed))
    import fmpy
    library = tmp_path / "PainleveRod.dylib"
    done = subprocess.run([sys.executable, "-m", "ziglang", "cc", "-target", "aarch64-macos.11.0", "-shared", "-O1",
                           "-std=c99", f"-I{sources}", f"-I{pathlib.Path(fmpy.__file__).parent / 'c-code'}",
                           *(str(sources / f) for f in listed), "-o", str(library)],
                          capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    (arch, body), = macho.slices(library.read_bytes())
    s = macho.parse(body)
    assert arch == "arm64" and s.dylibs == ["/usr/lib/libSystem.B.dylib"], s.dylibs
    # Co-Simulation is in: CVODE from sources/ was compiled in (SUNDIALS 7's context), and the
    # library exports every function of its FMI version.
    assert b"SUNContext_PushErrHandler" in body
    exported = exports(library, "arm64")
    assert fmi_functions(version) <= exported, sorted(fmi_functions(version) - exported)
