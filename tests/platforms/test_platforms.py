# SPDX-License-Identifier: BSD-2-Clause
"""One FMU per model and FMI version with every platform's binary in it
(build/platforms/, `bash run.sh platforms`), and the same numbers on every platform.

Each binary (win64 under wine64, aarch64 under qemu-user) runs the same cases, Model
Exchange and Co-Simulation, through the project's platform driver compiled for its platform
(tests/helpers/platform_binaries.py); every output at every communication point is compared
with x86_64-linux's. The models do the same IEEE operations everywhere (no fused multiply-add,
docs/platforms.md), so the rod agrees to 1e-12 relative or closer."""
import pathlib
import subprocess
import sys
import zipfile

import pytest
from fmpy import read_model_description, supported_platforms

from helpers import platform_binaries as pb
from painleve.experiments.case import horizon

ROOT = pathlib.Path(__file__).resolve().parents[2]
PLATFORMS = ROOT / "build" / "platforms"
sys.path.insert(0, str(ROOT / "bench"))

FMI2_FOLDERS = {"linux64", "win64", "darwin64"}
FMI3_FOLDERS = {"x86_64-linux", "x86_64-windows", "aarch64-linux", "x86_64-darwin", "aarch64-darwin"}
RTOL = 1e-12


def native_fmus():
    """Every FMU the native build makes (FMI 2.0 and 3.0, whatever models it has)."""
    build = ROOT / "build"
    return sorted(str(p.relative_to(build)) for pattern in ("*.fmu", "fmi3/*.fmu") for p in build.glob(pattern))


FMUS = native_fmus()


def test_every_model_of_the_build_has_a_multi_platform_fmu():
    assert FMUS, "the native build (build/) has no FMU"
    missing = [f for f in FMUS if not (PLATFORMS / f).is_file()]
    assert not missing, f"not in {PLATFORMS} (bash run.sh platforms): {missing}"


@pytest.mark.parametrize("fmu", FMUS)
def test_every_platform_is_in_the_fmu(fmu):
    """fmpy (0.3.32) lists linux64, win64 and darwin64 for both versions; it knows no
    aarch64-linux or aarch64-darwin, so the FMI 3.0 archive is read for those folders
    (docs/platforms.md)."""
    assert set(supported_platforms(str(PLATFORMS / fmu))) >= {"c-code", "linux64", "win64", "darwin64"}
    with zipfile.ZipFile(PLATFORMS / fmu) as z:
        folders = {pathlib.PurePosixPath(n).parent.name for n in z.namelist()
                   if n.startswith("binaries/") and n.endswith((".so", ".dll", ".dylib"))}
    assert folders == (FMI3_FOLDERS if fmu.startswith("fmi3/") else FMI2_FOLDERS)


def pe_dump(path):
    return subprocess.run(["x86_64-w64-mingw32-objdump", "-p", str(path)], capture_output=True, text=True,
                          check=True).stdout


@pytest.mark.parametrize("fmu", FMUS)
def test_windows_dll_imports_system_dlls_and_exports_its_fmi_version_only(fmu, tmp_path):
    fmu_dir = pb.unpack(PLATFORMS / fmu, tmp_path)
    md = read_model_description(str(fmu_dir / "modelDescription.xml"))
    prefix = "fmi3" if md.fmiVersion.startswith("3") else "fmi2"
    folder = "x86_64-windows" if prefix == "fmi3" else "win64"
    dump = pe_dump(fmu_dir / "binaries" / folder / f"{md.modelExchange.modelIdentifier}.dll")
    imports = {line.split(":")[1].strip().lower() for line in dump.splitlines() if "DLL Name:" in line}
    assert imports and imports <= {"kernel32.dll", "msvcrt.dll"}, imports
    table = dump.split("[Ordinal/Name Pointer] Table")[1].split("\n\n")[0]
    exports = [line.split()[-1] for line in table.splitlines() if line.strip().startswith("[")]
    assert f"{prefix}Instantiate" in exports or f"{prefix}InstantiateModelExchange" in exports
    assert all(name.startswith(prefix) for name in exports), [n for n in exports if not n.startswith(prefix)]


@pytest.mark.parametrize("target,objdump", [("x86_64-linux", "objdump"), ("aarch64-linux", "aarch64-linux-gnu-objdump")])
@pytest.mark.parametrize("fmu", FMUS)
def test_linux_library_exports_its_fmi_version_only(fmu, target, objdump, tmp_path):
    fmu_dir = pb.unpack(PLATFORMS / fmu, tmp_path)
    md = read_model_description(str(fmu_dir / "modelDescription.xml"))
    prefix = "fmi3" if md.fmiVersion.startswith("3") else "fmi2"
    if prefix == "fmi2" and target == "aarch64-linux":
        assert not (fmu_dir / "binaries" / "aarch64-linux").exists()   # FMI 2.0 names no folder: docs/platforms.md
        return
    library = fmu_dir / "binaries" / pb.folder(target, int(prefix[3])) / f"{md.modelExchange.modelIdentifier}.so"
    dump = subprocess.run([objdump, "-T", str(library)], capture_output=True, text=True, check=True).stdout
    exported = [line.split()[-1] for line in dump.splitlines() if " g " in line and "*UND*" not in line
                and "DF" in line]
    assert exported and all(name.startswith(prefix) for name in exported), exported


def outputs_of(md):
    return [v.name for v in md.modelVariables if v.type in ("Real", "Float64") and v.variability == "continuous"
            and v.causality in ("output", "local")]


def cases_of(md):
    """Both interfaces over the default experiment; for PainleveRod also the benchmark's IWC cases."""
    e = md.defaultExperiment
    cases = [(kind, float(e.startTime), float(e.stopTime), float(e.stopTime) / 50, {}) for kind in ("CS", "ME")]
    if md.modelName == "PainleveRod":
        from bench_runners import cases_at
        for case in cases_at(1e-2)[:3] + cases_at(1e-3)[3:]:
            stop = horizon(case)
            for kind in ("CS", "ME"):
                cases.append((kind, 0.0, stop, stop / 40, dict(case.start_values())))
    return cases


@pytest.fixture(scope="module")
def drivers(tmp_path_factory):
    out = tmp_path_factory.mktemp("drivers")
    return {target: pb.build_driver(target, out) for target in pb.TARGETS}


@pytest.fixture(scope="module")
def wine_prefix(tmp_path_factory):
    return tmp_path_factory.mktemp("wine")


# Where a platform's libm moves a result, the bound and why (docs/platforms.md). ShakerTable's
# drive F0 sin(2 pi f t): mingw-w64's sin differs from glibc's in the last bits (its drive_force
# by 1e-19 of F0, and Model Exchange, with no adaptive steps, stays within 1e-17), but CVODE's
# error test then takes other steps, so Co-Simulation differs by what CVODE's steps at the
# default tolerance (1e-6) leave: within 100 tolerances of the outputs' scale (measured: 1.4e-5).
# TwoLinkArm the same way: its sin and cos of two angles differ in the last bits on mingw-w64
# (Model Exchange stays within 1e-12), and the Co-Simulation integrator's error control takes
# other steps through the stiff contact (measured: 1.7e-10).
LIBM_BOUND = {("ShakerTable", "x86_64-windows", "CS"): 100 * 1e-6,
              ("TwoLinkArm", "x86_64-windows", "CS"): 100 * 1e-6}


@pytest.mark.parametrize("fmu", FMUS)
def test_every_platform_gives_x86_64_linux_numbers(fmu, drivers, wine_prefix, tmp_path):
    fmu_dir = pb.unpack(PLATFORMS / fmu, tmp_path)
    md = read_model_description(str(fmu_dir / "modelDescription.xml"))
    cases, outputs = cases_of(md), outputs_of(md)
    kinds = [c[0] for c in cases]
    targets = [t for t in pb.TARGETS if md.fmiVersion.startswith("3") or pb.TARGETS[t]["fmi2"]]
    runs = {t: pb.parse(pb.run_binary(t, drivers[t], fmu_dir, cases, outputs, wine_prefix)) for t in targets}
    reference = runs["x86_64-linux"]
    # The reference ran: every case reached its stop time without an error.
    assert len(reference) == len(cases) and all(not s and len(rows) > 40 for _, s, rows in reference), \
        [(k, s, len(rows)) for k, s, rows in reference]
    for target in targets[1:]:
        worst = pb.differences(reference, runs[target], kinds, outputs)
        print(fmu, target, max(worst.values()))
        over = {key: w for key, w in worst.items() if w > LIBM_BOUND.get((md.modelName, target, key[0]), RTOL)}
        assert not over, f"{target} differs from x86_64-linux (relative to each output's scale): {over}"
